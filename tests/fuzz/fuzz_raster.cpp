// Fuzz target: the tile rasterizer (raster/rasterizer.h) fed arbitrary float triangles, checked
// pixel for pixel against the scalar reference (raster/reference_rasterizer.h): no crash, no
// out-of-bounds access (the sanitizers watch), identical triangle ids and bit-identical depths
// on every input, whatever the tile size and cull mode.
//
// Input layout (short inputs are padded with zeros):
//   byte 0, 1   viewport width, height: 1 + b % 48 (small, so each run stays fast)
//   byte 2      bits 0-1 tile size 16 << k; bits 2-3 cull mode; bits 4-5 view_projection:
//               0 identity (positions are clip space with w = 1), 1 a perspective camera,
//               2 sixteen raw floats from the input, 3 a perspective with a raw-float eye
//   byte 3      vertex count (0..255)
//   then        the matrix floats (mode 2: 16, mode 3: 3), 3 floats per vertex, and the rest
//               as triangles of three one-byte indices (indices past the vertex count are
//               out of range on purpose: the rasterizer must skip them)
#include <cstring>
#include <stdexcept>

#include "raster/core/camera.h"
#include "raster/pipeline/rasterizer.h"
#include "raster/pipeline/reference_rasterizer.h"
#include "tests/fuzz/fuzz_target.h"

namespace tessera::fuzz {
namespace {

class Reader {
public:
    explicit Reader(Bytes data) : data_(data) {}
    uint8_t byte() { return at_ < data_.size() ? data_[at_++] : 0; }
    float real() {
        uint8_t b[4] = {byte(), byte(), byte(), byte()};
        float f;
        std::memcpy(&f, b, 4);
        return f;
    }
    bool empty() const { return at_ >= data_.size(); }

private:
    Bytes data_;
    size_t at_ = 0;
};

std::string compare(const VisibilityBuffer& fast, const VisibilityBuffer& reference) {
    if (fast.triangle.size() != reference.triangle.size() || fast.depth.size() != reference.depth.size())
        return "buffer sizes differ";
    for (size_t i = 0; i < fast.triangle.size(); ++i) {
        const int x = int(i % size_t(fast.width)), y = int(i / size_t(fast.width));
        if (fast.triangle[i] != reference.triangle[i])
            return "pixel (" + std::to_string(x) + ", " + std::to_string(y) + "): fast id " +
                   std::to_string(fast.triangle[i]) + ", reference " + std::to_string(reference.triangle[i]);
        if (std::memcmp(&fast.depth[i], &reference.depth[i], sizeof(float)) != 0)
            return "pixel (" + std::to_string(x) + ", " + std::to_string(y) + "): depths differ";
    }
    return "";
}

}  // namespace

std::string raster_input(Bytes data) {
    Reader in(data);
    const int width = 1 + in.byte() % 48, height = 1 + in.byte() % 48;
    const uint8_t flags = in.byte();
    pipeline::RasterOptions options;
    options.tile_size = 16 << (flags & 3);
    options.cull = (flags >> 2 & 3) == 1 ? pipeline::CullMode::back : (flags >> 2 & 3) == 2 ? pipeline::CullMode::front : pipeline::CullMode::none;
    const int vertices = in.byte();

    glm::mat4 vp(1.0f);
    Camera camera;
    camera.aspect = float(width) / float(height);
    switch (flags >> 4 & 3) {
        case 0: break;
        case 1: vp = camera.view_projection(); break;
        case 2:
            for (int c = 0; c < 4; ++c)
                for (int r = 0; r < 4; ++r) vp[c][r] = in.real();
            break;
        case 3:
            camera.eye = {in.real(), in.real(), in.real()};
            vp = camera.view_projection();
            break;
    }
    Mesh mesh;
    for (int v = 0; v < vertices; ++v) mesh.positions.push_back({in.real(), in.real(), in.real()});
    while (!in.empty()) mesh.indices.insert(mesh.indices.end(), {in.byte(), in.byte(), in.byte()});

    const pipeline::Viewport viewport(width, height);
    VisibilityBuffer fast, reference;
    pipeline::Rasterizer rasterizer;
    pipeline::RasterStats stats;
    rasterizer.render(mesh, vp, viewport, options, fast, {}, nullptr, &stats);
    pipeline::reference_rasterize(mesh, vp, viewport, options, reference);
    if (stats.triangles != mesh.triangle_count()) return "stats count the wrong number of triangles";
    return compare(fast, reference);
}

}  // namespace tessera::fuzz

TESSERA_FUZZ_ENTRY(raster_input)
