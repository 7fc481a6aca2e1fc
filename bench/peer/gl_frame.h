// One frame of a mesh rendered by OpenGL (the current context: llvmpipe through OSMesa) into
// framebuffer objects, with readback in tessera's conventions: rows top to bottom, triangle
// ids as in raster/visibility.h, window depth z_ndc * 0.5 + 0.5.
#pragma once
#include <cstdint>
#include <vector>

#include "raster/camera.h"
#include "raster/mesh.h"

namespace tessera::peer {

enum class Shade { id, depth, normal, phong };
enum class Cull { none, back, front };

struct FrameOptions {
    int width = 1920;
    int height = 1080;
    Shade shade = Shade::phong;
    Cull cull = Cull::back;
    bool triangle_ids = false;  // also render the triangle-id target (costs a second write)
};

class GlFrame {
public:
    // Uploads the mesh once and builds the program and targets; throws tessera::Error with
    // the GL log when a shader does not compile or a target is incomplete.
    GlFrame(const Mesh& mesh, const Camera& camera, const FrameOptions& options);
    ~GlFrame();
    GlFrame(const GlFrame&) = delete;
    GlFrame& operator=(const GlFrame&) = delete;

    // Clears, draws every triangle and waits for llvmpipe to finish (glFinish), so a timer
    // around it measures the whole frame, not the queueing of commands.
    void render();

    std::vector<uint8_t> colour_rgba8() const;     // width*height*4
    std::vector<uint32_t> triangle_ids() const;    // needs FrameOptions::triangle_ids
    std::vector<float> window_depth() const;       // width*height

private:
    template <class T>
    std::vector<T> read(unsigned attachment, unsigned format, unsigned type, int channels) const;

    FrameOptions options_;
    unsigned program_ = 0, vertex_array_ = 0, framebuffer_ = 0;
    unsigned buffers_[4] = {};        // positions, normals, uvs, indices
    unsigned renderbuffers_[3] = {};  // colour, triangle id, depth
    int element_count_ = 0;
    bool indexed_ = true;
};

}  // namespace tessera::peer
