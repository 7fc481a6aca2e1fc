// Test support for the shading tests: a brute-force visibility pass (one ray per pixel centre
// against every triangle, nearest hit wins) so that the shading goldens do not depend on the
// rasterizer, the same scenes through the real frame path (FrameRenderer) to compare with it,
// and image comparison with a tolerance (golden images: a diff image on failure).
#pragma once
#include <glm/glm.hpp>

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "raster/io/image_io.h"
#include "raster/output/frame_encoding.h"
#include "raster/render/frame_renderer.h"
#include "raster/scene/scene.h"
#include "raster/scene_file/scene_build.h"
#include "raster/shade/frame_shading.h"
#include "raster/shade/outline.h"

namespace tessera::test {

// Ray through the centre of pixel (x, y), as FrameShading's background computes it.
inline glm::vec3 pixel_ray(const Camera& camera, int width, int height, int x, int y) {
    const glm::mat4 view = camera.view(), projection = camera.projection();
    const float xn = 2.0f * (float(x) + 0.5f) / float(width) - 1.0f;
    const float yn = 1.0f - 2.0f * (float(y) + 0.5f) / float(height);
    const glm::vec3 u(view[0][0], view[1][0], view[2][0]), v(view[0][1], view[1][1], view[2][1]),
        w(view[0][2], view[1][2], view[2][2]);
    return u * (xn / projection[0][0]) + v * (yn / projection[1][1]) - w;
}

// Moeller-Trumbore; returns the ray parameter or -1.
inline float intersect(glm::vec3 origin, glm::vec3 dir, glm::vec3 a, glm::vec3 b, glm::vec3 c) {
    const glm::vec3 e1 = b - a, e2 = c - a, p = glm::cross(dir, e2);
    const float det = glm::dot(e1, p);
    if (std::abs(det) < 1e-12f) return -1.0f;
    const float inv = 1.0f / det;
    const glm::vec3 s = origin - a;
    const float u = glm::dot(s, p) * inv;
    if (u < 0.0f || u > 1.0f) return -1.0f;
    const glm::vec3 q = glm::cross(s, e1);
    const float v = glm::dot(dir, q) * inv;
    if (v < 0.0f || u + v > 1.0f) return -1.0f;
    return glm::dot(e2, q) * inv;
}

// Nearest opaque triangle per pixel and its window depth (read by the toon outlines).
inline VisibilityBuffer cast_visibility(const scene::BakedScene& baked, const scene::Scene& scene, int width, int height,
                                        std::vector<float>* nearest = nullptr) {
    VisibilityBuffer vis;
    vis.reset(width, height);
    if (nearest) nearest->assign(size_t(width) * size_t(height), 1e30f);
    const Mesh& m = baked.mesh;
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            const glm::vec3 dir = pixel_ray(scene.camera, width, height, x, y);
            float best = 1e30f;
            for (size_t t = 0; t < m.triangle_count(); ++t) {
                if (scene.materials[baked.triangle_material[t]].transparent()) continue;
                const float d = intersect(scene.camera.eye, dir, m.positions[m.indices[3 * t]],
                                          m.positions[m.indices[3 * t + 1]], m.positions[m.indices[3 * t + 2]]);
                if (d > 0.0f && d < best) {
                    best = d;
                    vis.triangle[size_t(y) * size_t(width) + size_t(x)] = uint32_t(t);
                }
            }
            if (nearest) (*nearest)[size_t(y) * size_t(width) + size_t(x)] = best;
            if (best < 1e30f) {
                const glm::vec4 clip = scene.camera.view_projection() * glm::vec4(scene.camera.eye + dir * best, 1.0f);
                vis.depth[size_t(y) * size_t(width) + size_t(x)] = clip.z / clip.w * 0.5f + 0.5f;
            }
        }
    return vis;
}

// The full test pipeline: bake, cast, shade the opaque pass, then blend the transparent
// triangles' covered pixels in submission (triangle id) order.
inline Frame render_scene(const scene::Scene& scene, int width, int height) {
    const scene::BakedScene baked = scene::bake(scene);
    std::vector<float> nearest;
    VisibilityBuffer vis = cast_visibility(baked, scene, width, height, &nearest);
    shade::RenderState state{scene.camera, width, height, scene.lights};
    const shade::FrameShading shading(baked, scene, state);
    Frame frame = shade::shade_visibility(shading, vis);
    std::vector<shade::CoveredPixel> transparent;
    const Mesh& m = baked.mesh;
    for (size_t t = 0; t < m.triangle_count(); ++t) {
        if (!scene.materials[baked.triangle_material[t]].transparent()) continue;
        for (int y = 0; y < height; ++y)
            for (int x = 0; x < width; ++x) {
                const float d = intersect(scene.camera.eye, pixel_ray(scene.camera, width, height, x, y),
                                          m.positions[m.indices[3 * t]], m.positions[m.indices[3 * t + 1]],
                                          m.positions[m.indices[3 * t + 2]]);
                if (d > 0.0f && d < nearest[size_t(y) * size_t(width) + size_t(x)])
                    transparent.push_back({x, y, uint32_t(t)});
            }
    }
    Tile whole;
    whole.rect = {0, 0, width, height};
    whole.colour = frame.pixels.data();
    whole.colour_stride = size_t(width);
    shade::blend_fragments(shading, transparent, whole);
    shade::draw_outlines(vis, scene.camera, baked.triangle_material, scene.materials, frame.pixels, 0, height);
    return frame;
}

// The scene through the frame path the `tessera render` command uses: tile rasterizer,
// shading, transparent triangles blended per tile; time 0, no shadows.
inline Frame rasterize(const scene::Scene& scene, int width, int height) {
    render::AnimatedScene still = render::still_scene(scene);
    render::FrameRenderer renderer(still, width, height, render::RendererKind::raster, render::ShadowMode::none);
    return renderer.render(0.0f);
}

// How many pixels of two equally sized 8-bit RGBA images differ by more than `tolerance` (of
// 255) in some channel. With `diff`: an image of the colour differences x8, for people.
inline size_t count_differing(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b, int tolerance,
                              std::vector<uint8_t>* diff = nullptr) {
    if (diff) diff->assign(a.size(), 255);
    size_t bad = 0;
    for (size_t i = 0; i < a.size() / 4; ++i) {
        bool pixel_bad = false;
        for (int c = 0; c < 4; ++c) {
            const int d = std::abs(int(a[4 * i + size_t(c)]) - int(b[4 * i + size_t(c)]));
            pixel_bad |= d > tolerance;
            if (diff && c < 3) (*diff)[4 * i + size_t(c)] = uint8_t(std::min(255, d * 8));
        }
        bad += pixel_bad;
    }
    return bad;
}

inline std::filesystem::path golden_path(const std::string& name) {
    return std::filesystem::path(TESSERA_TEST_DATA) / "golden" / (name + ".png");
}

// Compares the frame's 8-bit sRGB encoding with tests/data/golden/NAME.png: at most
// `max_bad_fraction` of the pixels may differ by more than `tolerance` (of 255) in a channel.
// Golden files are committed; TESSERA_UPDATE_GOLDEN=1 rewrites them (never done implicitly:
// a missing golden is a failure). On failure the actual image and a diff image (differences
// x8) are written to the temporary directory and named in `why`.
inline bool matches_golden(const Frame& frame, const std::string& name, std::string& why,
                           int tolerance = 3, double max_bad_fraction = 0.002) {
    const std::vector<uint8_t> actual = output::encode_srgb8(frame);
    const io::ImageView view{frame.width, frame.height, 4, io::PixelType::u8, actual.data()};
    if (const char* update = std::getenv("TESSERA_UPDATE_GOLDEN"); update && std::string(update) == "1") {
        io::write_image(golden_path(name), view);
        return true;
    }
    if (!std::filesystem::exists(golden_path(name))) {
        why = "golden " + golden_path(name).string() + " is missing (TESSERA_UPDATE_GOLDEN=1 creates it)";
        return false;
    }
    const io::FloatImage golden = io::read_image(golden_path(name));
    if (golden.width != frame.width || golden.height != frame.height || golden.channels != 4) {
        why = "golden " + name + " has a different size or channel count";
        return false;
    }
    std::vector<uint8_t> expected(golden.pixels.size());
    for (size_t i = 0; i < expected.size(); ++i) expected[i] = uint8_t(int(golden.pixels[i] * 255.0f + 0.5f));
    std::vector<uint8_t> diff;
    const size_t bad = count_differing(expected, actual, tolerance, &diff);
    if (double(bad) <= max_bad_fraction * double(actual.size() / 4)) return true;
    const auto dir = std::filesystem::temp_directory_path() / "tessera_golden_failures";
    std::filesystem::create_directories(dir);
    io::write_image(dir / (name + "_actual.png"), view);
    io::write_image(dir / (name + "_diff.png"), {frame.width, frame.height, 4, io::PixelType::u8, diff.data()});
    why = std::to_string(bad) + " pixels differ from golden " + name + "; see " + (dir / (name + "_diff.png")).string();
    return false;
}

}  // namespace tessera::test
