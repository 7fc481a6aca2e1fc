// An off-screen OpenGL context on Mesa's llvmpipe (through OSMesa), for the peer renderer that
// renders tessera's workloads with a production rasterizer.
//
// llvmpipe reads its thread count from the environment when the context's screen is created,
// so LP_NUM_THREADS is set here, before OSMesaCreateContext*, never after.
#pragma once
#include <string>

struct osmesa_context;

namespace tessera::peer {

class OsMesaContext {
public:
    // raster_threads > 0 sets LP_NUM_THREADS (llvmpipe's rasterizer threads; its setup and
    // binning run on the calling thread besides them); 0 keeps llvmpipe's default (one per
    // CPU). Asks for a GL 3.3 core context, falling back to the compatibility profile.
    // Throws tessera::Error when no context can be made current.
    explicit OsMesaContext(int raster_threads);
    ~OsMesaContext();
    OsMesaContext(const OsMesaContext&) = delete;
    OsMesaContext& operator=(const OsMesaContext&) = delete;

    bool core_profile() const { return core_profile_; }
    // "llvmpipe (LLVM 15.0.6, 256 bits)", "4.5 (Core Profile) Mesa 22.3.6", ...
    std::string renderer() const;
    std::string version() const;

private:
    osmesa_context* context_ = nullptr;
    bool core_profile_ = false;
    // The context renders into framebuffer objects; OSMesa still needs a bound colour buffer,
    // so a single RGBA pixel is bound.
    unsigned char window_[4] = {};
};

}  // namespace tessera::peer
