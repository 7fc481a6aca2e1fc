#include "raster/core/pixel_rays.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace tessera {

PixelRays::PixelRays(const glm::mat4& view_projection, int width, int height)
    : view_projection_(view_projection), width_(width), height_(height) {
    if (width <= 0 || height <= 0)
        throw std::invalid_argument("image size " + std::to_string(width) + "x" +
                                    std::to_string(height) + " is not positive");
    // inverse * (x_ndc, y_ndc, z, 1) with x_ndc = 2x/W - 1, y_ndc = 1 - 2y/H (rows top to
    // bottom, camera.h) is affine in the window position (x, y): fold the mapping in, once,
    // in double.
    const glm::dmat4 inverse = inverse_ = glm::inverse(glm::dmat4(view_projection));
    const glm::dvec4 per_x = inverse[0] * (2.0 / width), per_y = inverse[1] * (-2.0 / height);
    const glm::dvec4 at_zero = inverse[3] - inverse[0] + inverse[1];
    near_ = {at_zero - inverse[2], per_x, per_y};
    far_ = {at_zero + inverse[2], per_x, per_y};
}

void PixelRays::ray(float x_centre, float y_centre, glm::vec3& origin,
                    glm::vec3& direction) const {
    const glm::dvec4 on_near = near_.at(x_centre, y_centre);
    const glm::dvec4 on_far = far_.at(x_centre, y_centre);
    const glm::dvec3 near_point = glm::dvec3(on_near) / on_near.w;
    origin = glm::vec3(near_point);
    direction = glm::vec3(glm::dvec3(on_far) / on_far.w - near_point);
}

namespace {

// PixelRays::rays' loop, with __restrict parameters (GCC honours restrict on parameters, not
// on locals) so that it vectorises: Affine::at (origin + x * per_x + y * per_y) and the
// divisions by w, per component.
void rays_of(size_t n, const float* __restrict x_centre, const float* __restrict y_centre, const glm::dvec4 no,
             const glm::dvec4 fo, const glm::dvec4 px, const glm::dvec4 py, float* __restrict ox,
             float* __restrict oy, float* __restrict oz, float* __restrict dx, float* __restrict dy,
             float* __restrict dz) {
    for (size_t i = 0; i < n; ++i) {
        const double x = x_centre[i], y = y_centre[i];
        const double nw = (no.w + x * px.w) + y * py.w, fw = (fo.w + x * px.w) + y * py.w;
        const double nx = ((no.x + x * px.x) + y * py.x) / nw, ny = ((no.y + x * px.y) + y * py.y) / nw,
                     nz = ((no.z + x * px.z) + y * py.z) / nw;
        const double fx = ((fo.x + x * px.x) + y * py.x) / fw, fy = ((fo.y + x * px.y) + y * py.y) / fw,
                     fz = ((fo.z + x * px.z) + y * py.z) / fw;
        ox[i] = float(nx);
        oy[i] = float(ny);
        oz[i] = float(nz);
        dx[i] = float(fx - nx);
        dy[i] = float(fy - ny);
        dz[i] = float(fz - nz);
    }
}

}  // namespace

void PixelRays::rays(size_t n, const float* x_centre, const float* y_centre, const RayArrays& out) const {
    rays_of(n, x_centre, y_centre, near_.origin, far_.origin, near_.per_x, near_.per_y, out.ox, out.oy, out.oz,
            out.dx, out.dy, out.dz);
}

float PixelRays::window_depth(const glm::vec3& world) const {
    const glm::dvec4 clip = view_projection_ * glm::dvec4(glm::dvec3(world), 1.0);
    return float(clip.z / clip.w * 0.5 + 0.5);
}

PixelRays::DepthPlane PixelRays::depth_plane(const glm::vec3& a, const glm::vec3& b,
                                             const glm::vec3& c) const {
    // World plane (n, -n.a); in clip coordinates it is the row vector plane * inverse, so a
    // point with NDC (x, y, z) on it satisfies q.x x + q.y y + q.z z + q.w = 0.
    const glm::dvec3 pa(a), n = glm::cross(glm::dvec3(b) - pa, glm::dvec3(c) - pa);
    const glm::dvec4 q = glm::dvec4(n, -glm::dot(n, pa)) * inverse_;
    DepthPlane plane;
    if (q.z == 0.0 || !std::isfinite(q.z)) return plane;
    // z_ndc = -(q.x x_ndc + q.y y_ndc + q.w) / q.z with x_ndc = 2X/W - 1, y_ndc = 1 - 2Y/H;
    // window depth = z_ndc / 2 + 1/2.
    const double kx = -q.x / q.z, ky = -q.y / q.z, k0 = -q.w / q.z;
    plane.per_x = 0.5 * kx * 2.0 / width_;
    plane.per_y = -0.5 * ky * 2.0 / height_;
    plane.at_zero = 0.5 * (k0 - kx + ky) + 0.5;
    plane.valid = std::isfinite(plane.per_x) && std::isfinite(plane.per_y) &&
                  std::isfinite(plane.at_zero);
    return plane;
}

}  // namespace tessera
