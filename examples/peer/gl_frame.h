// One frame of a mesh rendered by OpenGL (the current context: llvmpipe through OSMesa) into
// framebuffer objects, with readback in tessera's conventions: rows top to bottom, triangle
// ids and window depth (z_ndc * 0.5 + 0.5) in a VisibilityBuffer, so tessera's writers
// (raster/visibility_io.h) write the peer's files too.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <string>
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
    // Samples per pixel: 1, or a multisample count llvmpipe supports for every target (else
    // GlFrame throws). Multisampled frames read back only ids, every sample's.
    int samples = 1;
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
    // Multisampled: samples and sample_triangle hold every sample's id, in tessera's sample
    // order (pipeline/sample_pattern.h); triangle and depth stay empty.
    VisibilityBuffer visibility() const;

    // The sample positions llvmpipe reports for the frame (GL_SAMPLE_POSITION, pixel units
    // from the pixel's corner at row and column 0, in the frame's top-down rows), in GL's order.
    const std::vector<glm::vec2>& gl_sample_positions() const { return gl_positions_; }
    // Empty when llvmpipe samples at tessera's positions (in any order: the ids are read back
    // in tessera's), else what differs; visibility() then refuses the multisampled ids.
    std::string sample_position_mismatch() const;

private:
    template <class T>
    std::vector<T> read(unsigned attachment, unsigned format, unsigned type, int channels) const;

    void make_multisample_targets();
    VisibilityBuffer sample_ids() const;

    FrameOptions options_;
    unsigned program_ = 0, vertex_array_ = 0, framebuffer_ = 0;
    unsigned buffers_[4] = {};        // positions, normals, uvs, indices
    unsigned renderbuffers_[3] = {};  // colour, triangle id, depth
    // Multisampled: the ids in a multisample texture, and a program that copies one sample of
    // it into a single-sample target per pass (texelFetch of a usampler2DMS).
    unsigned sample_texture_ = 0, copy_program_ = 0, copy_vertex_array_ = 0, copy_framebuffer_ = 0,
             copy_renderbuffer_ = 0;
    std::vector<glm::vec2> gl_positions_;
    std::vector<int> gl_sample_of_;  // tessera's sample s is GL's sample gl_sample_of_[s]
    int element_count_ = 0;
    bool indexed_ = true;
};

}  // namespace tessera::peer
