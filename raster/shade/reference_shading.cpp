#include "raster/shade/reference_shading.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "raster/pipeline/barycentrics.h"
#include "raster/core/visibility.h"
#include "procedural/hash.h"

namespace tessera::shade {

ShadeMode parse_shade_mode(const std::string& text) {
    if (text == "id") return ShadeMode::id;
    if (text == "depth") return ShadeMode::depth;
    if (text == "normal") return ShadeMode::normal;
    if (text == "phong") return ShadeMode::phong;
    throw std::invalid_argument("--shade expects id, depth, normal or phong, got '" + text + "'");
}

PhongLight PhongLight::from(const Camera& camera) {
    const float d = glm::length(camera.lookat - camera.eye);
    const glm::vec3 fwd = (camera.lookat - camera.eye) / d;
    const glm::vec3 right = glm::normalize(glm::cross(fwd, camera.up));
    const glm::vec3 up2 = glm::cross(right, fwd);
    return {camera.eye, camera.eye + right * (0.4f * d) + up2 * (0.5f * d) + fwd * (0.2f * d)};
}

void fetch_triangle_attributes(const pipeline::TileContext& ctx, uint32_t id, TriangleAttributes& t) {
    const Mesh& mesh = *ctx.mesh;
    const uint32_t* index = &mesh.indices[3 * size_t(id)];
    t.id = id;
    t.barycentrics = pipeline::triangle_barycentrics(mesh, *ctx.clip, id, *ctx.viewport);
    for (int k = 0; k < 3; ++k) t.position[k] = mesh.positions[index[k]];
    if (mesh.normals.empty()) {
        const glm::vec3 n = glm::cross(t.position[1] - t.position[0], t.position[2] - t.position[0]);
        const float length = glm::length(n);
        const glm::vec3 face = length > 0.0f ? n / length : glm::vec3(0.0f, 0.0f, 1.0f);
        for (int k = 0; k < 3; ++k) t.normal[k] = face;
    } else {
        for (int k = 0; k < 3; ++k) t.normal[k] = mesh.normals[index[k]];
    }
    for (int k = 0; k < 3; ++k) t.uv[k] = mesh.uvs.empty() ? glm::vec2(0.0f) : mesh.uvs[index[k]];
}

uint32_t id_colour(uint32_t id) { return procedural::hash(0x7e55e7a, int32_t(id)); }

namespace {

// v / |v| as v * (1 / |v|): one division per vector rather than three, which the SIMD pass
// (where a 16-lane division costs as much as ten multiplies) repeats exactly; 0 where |v| = 0.
glm::vec3 safe_normalize(glm::vec3 v) {
    const float length = glm::length(v);
    return length > 0.0f ? v * (1.0f / length) : glm::vec3(0.0f);
}

}  // namespace

std::vector<uint8_t> rgb8_of(const std::vector<uint32_t>& rgba8) {
    std::vector<uint8_t> rgb8(rgba8.size() * 3);
    for (size_t i = 0; i < rgba8.size(); ++i) {
        rgb8[3 * i] = uint8_t(rgba8[i]);
        rgb8[3 * i + 1] = uint8_t(rgba8[i] >> 8);
        rgb8[3 * i + 2] = uint8_t(rgba8[i] >> 16);
    }
    return rgb8;
}

pipeline::TilePass make_reference_shading_pass(ShadeMode mode, const Camera& camera, std::vector<uint32_t>& rgba8) {
    const PhongLight phong = PhongLight::from(camera);
    const glm::vec3 eye = phong.eye, light = phong.light;
    return [mode, eye, light, &rgba8](const pipeline::TileContext& ctx) {
        TriangleAttributes t;
        const int width = ctx.viewport->width;
        for (int y = ctx.rect.y0; y < ctx.rect.y1; ++y)
            for (int x = ctx.rect.x0; x < ctx.rect.x1; ++x) {
                const size_t i = size_t(y - ctx.rect.y0) * ctx.stride + size_t(x - ctx.rect.x0);
                const uint32_t id = ctx.triangle[i];
                glm::vec3 c(0.0f);
                if (id != kNoTriangle) {
                    if (mode == ShadeMode::id) {
                        const uint32_t h = id_colour(id);
                        c = glm::vec3(float(h & 255), float((h >> 8) & 255), float((h >> 16) & 255)) / 255.0f;
                    } else if (mode == ShadeMode::depth) {
                        c = glm::vec3(ctx.depth[i]);
                    } else {
                        if (t.id != id) fetch_triangle_attributes(ctx, id, t);
                        float l[3];
                        t.barycentrics.at(float(x) + 0.5f, float(y) + 0.5f, l[0], l[1], l[2]);
                        const glm::vec3 n = safe_normalize(l[0] * t.normal[0] + l[1] * t.normal[1] + l[2] * t.normal[2]);
                        if (mode == ShadeMode::normal) {
                            c = n * 0.5f + 0.5f;
                        } else {
                            const glm::vec3 p = l[0] * t.position[0] + l[1] * t.position[1] + l[2] * t.position[2];
                            const glm::vec2 uv = l[0] * t.uv[0] + l[1] * t.uv[1] + l[2] * t.uv[2];
                            const glm::vec3 v = safe_normalize(eye - p);
                            const glm::vec3 n2 = glm::dot(n, v) < 0.0f ? -n : n;
                            const glm::vec3 lv = safe_normalize(light - p);
                            const glm::vec3 h = safe_normalize(lv + v);
                            const float s = std::floor(uv.x * 16.0f) + std::floor(uv.y * 8.0f);
                            const float checker = s - 2.0f * std::floor(s * 0.5f);  // GLSL mod(s, 2)
                            const glm::vec3 albedo = glm::mix(glm::vec3(0.80f, 0.35f, 0.20f),
                                                              glm::vec3(0.90f, 0.85f, 0.70f), checker);
                            c = albedo * (0.08f + 0.92f * std::max(glm::dot(n2, lv), 0.0f)) +
                                glm::vec3(0.5f * std::pow(std::max(glm::dot(n2, h), 0.0f), 48.0f));
                        }
                    }
                }
                if (ctx.colour)
                    ctx.colour[size_t(y - ctx.rect.y0) * ctx.colour_stride + size_t(x - ctx.rect.x0)] = glm::vec4(c, 1.0f);
                rgba8[size_t(y) * width + x] = pack_rgba8(quantise(c.r), quantise(c.g), quantise(c.b));
            }
    };
}

}  // namespace tessera::shade
