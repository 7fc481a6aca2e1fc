// One frame of a mesh rendered by OpenGL (the current context: llvmpipe through OSMesa) into
// framebuffer objects, with readback in tessera's conventions: rows top to bottom, triangle
// ids and window depth (z_ndc * 0.5 + 0.5) in a VisibilityBuffer, so tessera's writers
// (raster/visibility_io.h) write the peer's files too.
#pragma once
#include <cstdint>
#include <vector>

#include "raster/core/camera.h"
#include "raster/core/mesh.h"
#include "raster/shade/reference_shading.h"
#include "raster/pipeline/triangle_setup.h"
#include "raster/core/visibility.h"

namespace tessera::peer {

struct FrameOptions {
    int width = 1920;
    int height = 1080;
    shade::ShadeMode shade = shade::ShadeMode::phong;
    pipeline::CullMode cull = pipeline::CullMode::none;
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

    // 8-bit RGB, black where nothing covers, as `tessera raster --out-color` writes it.
    std::vector<uint8_t> colour_rgb8() const;
    // Window depth, and triangle ids when FrameOptions::triangle_ids (else kNoTriangle).
    VisibilityBuffer visibility() const;

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
