#include "raster/march/ray_generation.h"

#include <glm/gtc/matrix_inverse.hpp>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace tessera::march {

RayGenerator::RayGenerator(const Camera& camera, int width, int height)
    : eye_(camera.eye),
      forward_(glm::normalize(camera.lookat - camera.eye)),
      near_(camera.near),
      far_(camera.far),
      width_(width),
      height_(height) {
    if (width <= 0 || height <= 0)
        throw std::invalid_argument("ray generation: image size " + std::to_string(width) + "x" +
                                    std::to_string(height) + " is not positive");
    // Inverting in double keeps the far-plane directions accurate for large far/near ratios.
    const glm::dmat4 vp = glm::dmat4(camera.view_projection());
    const glm::dmat4 eye_translation =
        glm::translate(glm::dmat4(1.0), glm::dvec3(camera.eye));
    const double det = glm::determinant(vp);
    if (!std::isfinite(det) || det == 0.0)
        throw std::invalid_argument("ray generation: the camera's view-projection is singular "
                                    "(check eye, lookat, up, fov and the near/far planes)");
    view_projection_ = glm::mat4(vp);
    inverse_view_projection_ = glm::mat4(glm::inverse(vp));
    ray_dir_matrix_ = glm::mat4(glm::inverse(vp * eye_translation));
}

glm::vec2 RayGenerator::ndc(int x, int y, glm::vec2 offset) const {
    // + offset after + 0.5: exact for offset 0, so pixel centres keep their values.
    return {(float(x) + 0.5f + offset.x) / float(width_) * 2.0f - 1.0f,
            1.0f - (float(y) + 0.5f + offset.y) / float(height_) * 2.0f};
}

glm::vec3 RayGenerator::direction(int x, int y) const { return direction(x, y, glm::vec2(0.0f)); }

glm::vec3 RayGenerator::direction(int x, int y, glm::vec2 offset) const {
    const glm::vec2 n = ndc(x, y, offset);
    return glm::normalize(glm::vec3(ray_dir_matrix_ * glm::vec4(n.x, n.y, 1.0f, 1.0f)));
}

void RayGenerator::sample_packet(const int* x, const int* y, const glm::vec2* offset, int count,
                                 RayPacket& out) const {
    out.count = count;
    for (int i = 0; i < kMarchLanes; ++i) {
        const int lane = i < count ? i : 0;
        const glm::vec3 d = direction(x[lane], y[lane], offset[lane]);
        out.dx[i] = d.x;
        out.dy[i] = d.y;
        out.dz[i] = d.z;
        out.ox[i] = eye_.x;
        out.oy[i] = eye_.y;
        out.oz[i] = eye_.z;
    }
}

void RayGenerator::packet(int x0, int y, int count, RayPacket& out) const {
    out.count = count;
    const glm::mat4& m = ray_dir_matrix_;
    const float ny = 1.0f - (float(y) + 0.5f) / float(height_) * 2.0f;
    // Direction before normalisation is linear in x_ndc: base + x_ndc * column 0.
    const glm::vec3 base = glm::vec3(m[1]) * ny + glm::vec3(m[2]) + glm::vec3(m[3]);
    const glm::vec3 col0 = glm::vec3(m[0]);
    const float inv_w = 2.0f / float(width_);
    for (int i = 0; i < kMarchLanes; ++i) {
        const int lane_x = x0 + (i < count ? i : 0);
        const float nx = (float(lane_x) + 0.5f) * inv_w - 1.0f;
        const float x = base.x + col0.x * nx, yy = base.y + col0.y * nx, z = base.z + col0.z * nx;
        const float inv_len = 1.0f / std::sqrt(x * x + yy * yy + z * z);
        out.dx[i] = x * inv_len;
        out.dy[i] = yy * inv_len;
        out.dz[i] = z * inv_len;
        out.ox[i] = eye_.x;
        out.oy[i] = eye_.y;
        out.oz[i] = eye_.z;
    }
}

simd::vfloat RayGenerator::ndc_x(int x0) const {
    using simd::vfloat;
    const vfloat x = simd::to_float(simd::vint(x0) + simd::lane_index());
    return (x + vfloat(0.5f)) / vfloat(float(width_)) * vfloat(2.0f) - vfloat(1.0f);
}

namespace {

using simd::vfloat;

// Row `row` of m * (x, y, z, w) as glm computes it: (m0 x + m1 y) + (m2 z + m3 w).
vfloat transform_row(const glm::mat4& m, int row, vfloat x, float y, vfloat z, float w) {
    return (vfloat(m[0][row]) * x + vfloat(m[1][row] * y)) + (vfloat(m[2][row]) * z + vfloat(m[3][row] * w));
}

}  // namespace

simd::V3<vfloat> RayGenerator::directions(int x0, int y) const {
    const vfloat nx = ndc_x(x0);
    const float ny = ndc(x0, y).y;
    const glm::mat4& m = ray_dir_matrix_;
    const simd::V3<vfloat> v{transform_row(m, 0, nx, ny, vfloat(1.0f), 1.0f),
                             transform_row(m, 1, nx, ny, vfloat(1.0f), 1.0f),
                             transform_row(m, 2, nx, ny, vfloat(1.0f), 1.0f)};
    // glm::normalize: v * (1 / sqrt(dot(v, v))), dot as (x x + y y) + z z.
    const vfloat inv = vfloat(1.0f) / simd::sqrt((v.x * v.x + v.y * v.y) + v.z * v.z);
    return v * inv;
}

vfloat RayGenerator::distances_from_depth(int x0, int y, vfloat depth) const {
    const vfloat nx = ndc_x(x0);
    const float ny = ndc(x0, y).y;
    const glm::mat4& m = inverse_view_projection_;
    const vfloat z = depth * vfloat(2.0f) - vfloat(1.0f);
    const vfloat w = transform_row(m, 3, nx, ny, z, 1.0f);
    const vfloat px = transform_row(m, 0, nx, ny, z, 1.0f) / w - vfloat(eye_.x);
    const vfloat py = transform_row(m, 1, nx, ny, z, 1.0f) / w - vfloat(eye_.y);
    const vfloat pz = transform_row(m, 2, nx, ny, z, 1.0f) / w - vfloat(eye_.z);
    const vfloat length = simd::sqrt((px * px + py * py) + pz * pz);
    return simd::select(depth < vfloat(1.0f), length, vfloat(std::numeric_limits<float>::infinity()));
}

float RayGenerator::window_depth(const glm::vec3& world) const {
    const glm::vec4 clip = view_projection_ * glm::vec4(world, 1.0f);
    return clip.z / clip.w * 0.5f + 0.5f;
}

vfloat RayGenerator::window_depths(const simd::V3<vfloat>& world) const {
    const glm::mat4& m = view_projection_;
    auto row = [&](int r) {
        return (vfloat(m[0][r]) * world.x + vfloat(m[1][r]) * world.y) +
               (vfloat(m[2][r]) * world.z + vfloat(m[3][r] * 1.0f));
    };
    return row(2) / row(3) * vfloat(0.5f) + vfloat(0.5f);
}

float RayGenerator::distance_from_depth(int x, int y, float depth) const {
    if (!(depth < 1.0f)) return std::numeric_limits<float>::infinity();
    const glm::vec2 n = ndc(x, y);
    const glm::vec4 h = inverse_view_projection_ * glm::vec4(n.x, n.y, depth * 2.0f - 1.0f, 1.0f);
    return glm::length(glm::vec3(h) / h.w - eye_);
}

}  // namespace tessera::march
