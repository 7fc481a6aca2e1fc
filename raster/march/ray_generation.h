// Primary rays per pixel from the inverse view-projection ("rayDirMatrix"): the GPU version
// draws a full-screen quad and lets the vertex shader turn normalised device coordinates into a
// world-space direction with (E V P)^-1, where E translates by the eye position. The
// translation makes the matrix map NDC straight to eye-relative directions, so no per-pixel
// subtraction of the eye is needed; since a direction is normalised anyway, the homogeneous
// divide is skipped too (w > 0 for every point in front of the camera).
//
// Pixel centres follow raster/camera.h: x_ndc = (x + 0.5) / width * 2 - 1 and rows run top to
// bottom, y_ndc = 1 - (y + 0.5) / height * 2.
#pragma once
#include <glm/glm.hpp>

#include "raster/core/camera.h"
#include "raster/march/ray_packet.h"
#include "raster/simd/lane_math.h"

namespace tessera::march {

class RayGenerator {
public:
    // Throws std::invalid_argument for a non-positive size or a singular view-projection.
    RayGenerator(const Camera& camera, int width, int height);

    // The unit direction through the centre of pixel (x, y).
    glm::vec3 direction(int x, int y) const;

    // Rays through pixels (x0 .. x0+count-1, y); count in 1..kMarchLanes.
    void packet(int x0, int y, int count, RayPacket& out) const;

    // The unit direction through the point `offset` pixels (y down) from the centre of pixel
    // (x, y), which may lie outside the image: a multisample position (sample_pattern.h) or a
    // neighbour's centre.
    glm::vec3 direction(int x, int y, glm::vec2 offset) const;
    // Rays through such points, one per lane: lane i through `offset[i]` of pixel (x[i], y[i]);
    // count in 1..kMarchLanes (later lanes copy lane 0).
    void sample_packet(const int* x, const int* y, const glm::vec2* offset, int count, RayPacket& out) const;

    // direction() and distance_from_depth() for the kLanes pixels (x0 + i, y), one per lane
    // i, with their arithmetic in their order (glm's mat4 * vec4, normalize and length), so
    // each lane equals the one-pixel call bit for bit: the per-pixel passes' form.
    simd::V3<simd::vfloat> directions(int x0, int y) const;
    simd::vfloat distances_from_depth(int x0, int y, simd::vfloat depth) const;

    // Converts a world-space point to window depth (z_ndc * 0.5 + 0.5), the value the depth
    // buffer stores, so marched hits and rasterized triangles are compared in one space.
    float window_depth(const glm::vec3& world) const;
    // The same for kLanes points, one per lane (glm's mat4 * vec4 order): equal lane by lane.
    simd::vfloat window_depths(const simd::V3<simd::vfloat>& world) const;

    // Distance from the eye to the surface seen at pixel (x, y) with window depth `depth`
    // (the point is unprojected through the inverse view-projection); infinity for
    // depth >= 1, the cleared (empty) value: the fog treats it as the background at infinity.
    float distance_from_depth(int x, int y, float depth) const;

    // Distances along the unit direction `d` to the near and far planes: only hits between
    // them are visible (the rasterizer clips triangles to the same planes).
    float near_distance(glm::vec3 d) const { return near_ / glm::dot(d, forward_); }
    float far_distance(glm::vec3 d) const { return far_ / glm::dot(d, forward_); }
    simd::vfloat near_distances(const simd::V3<simd::vfloat>& d) const {  // glm::dot's order
        using simd::vfloat;
        return vfloat(near_) / ((d.x * vfloat(forward_.x) + d.y * vfloat(forward_.y)) + d.z * vfloat(forward_.z));
    }
    simd::vfloat far_distances(const simd::V3<simd::vfloat>& d) const {
        using simd::vfloat;
        return vfloat(far_) / ((d.x * vfloat(forward_.x) + d.y * vfloat(forward_.y)) + d.z * vfloat(forward_.z));
    }

    const glm::vec3& eye() const { return eye_; }
    int width() const { return width_; }
    int height() const { return height_; }

private:
    // NDC of the point `offset` pixels from the centre of pixel (x, y).
    glm::vec2 ndc(int x, int y, glm::vec2 offset = glm::vec2(0.0f)) const;
    simd::vfloat ndc_x(int x0) const;

    glm::mat4 ray_dir_matrix_;   // (E V P)^-1: NDC (x, y, 1, 1) -> eye-relative direction
    glm::mat4 view_projection_;  // world -> clip
    glm::mat4 inverse_view_projection_;
    glm::vec3 eye_;
    glm::vec3 forward_;  // unit view direction
    float near_;
    float far_;
    int width_;
    int height_;
};

}  // namespace tessera::march
