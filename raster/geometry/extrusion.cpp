#include "raster/geometry/extrusion.h"

#include <glm/gtc/constants.hpp>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "raster/geometry/param_surface.h"

namespace tessera::geometry {
namespace {

struct Frame {
    glm::vec3 t, n, b;
};

glm::vec3 unit_or(glm::vec3 v, glm::vec3 fallback) {
    const float len = glm::length(v);
    return len > 1e-20f && std::isfinite(len) ? v / len : fallback;
}

// Double reflection: reflect the previous frame in the bisecting plane of the two sample
// points, then in the plane that maps the reflected tangent onto the new tangent.
std::vector<Frame> rotation_minimising_frames(const BezierCurve<glm::vec3>& spine, int along) {
    std::vector<Frame> frames(size_t(along) + 1);
    glm::vec3 previous_t(0, 0, 1);
    for (int i = 0; i <= along; ++i) {
        const float s = float(i) / float(along);
        previous_t = unit_or(spine.derivative(s), previous_t);
        frames[size_t(i)].t = previous_t;
    }
    const glm::vec3 t0 = frames[0].t;
    const glm::vec3 up = std::abs(t0.y) < 0.99f ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0);
    frames[0].n = glm::normalize(up - glm::dot(up, t0) * t0);
    for (int i = 0; i < along; ++i) {
        const Frame& f = frames[size_t(i)];
        Frame& g = frames[size_t(i) + 1];
        const glm::vec3 v1 = spine.position(float(i + 1) / float(along)) - spine.position(float(i) / float(along));
        const float c1 = glm::dot(v1, v1);
        glm::vec3 rl = f.n, tl = f.t;
        if (c1 > 0.0f) {
            rl = f.n - (2.0f / c1) * glm::dot(v1, f.n) * v1;
            tl = f.t - (2.0f / c1) * glm::dot(v1, f.t) * v1;
        }
        const glm::vec3 v2 = g.t - tl;
        const float c2 = glm::dot(v2, v2);
        glm::vec3 r = c2 > 0.0f ? rl - (2.0f / c2) * glm::dot(v2, rl) * v2 : rl;
        g.n = unit_or(r - glm::dot(r, g.t) * g.t, f.n);  // re-orthogonalise against rounding
    }
    for (Frame& f : frames) f.b = glm::cross(f.t, f.n);
    return frames;
}

}  // namespace

Mesh extrude(const BezierCurve<glm::vec3>& spine, const BezierCurve<glm::vec2>& radii, int along,
             int around) {
    if (along < 1 || around < 3)
        throw std::invalid_argument("extrusion needs at least 1 x 3 quads, got " +
                                    std::to_string(along) + " x " + std::to_string(around));
    const std::vector<Frame> frames = rotation_minimising_frames(spine, along);
    constexpr float kTwoPi = 2.0f * glm::pi<float>();
    const SurfaceFunction surface = [&](float s, float v) {
        const Frame& f = frames[size_t(std::lround(s * float(along)))];
        const glm::vec3 d1 = spine.derivative(s), d2 = spine.second_derivative(s);
        const float speed = glm::length(d1);
        const glm::vec2 ab = radii.position(s), dab = radii.derivative(s);
        if (ab.x < 0.0f || ab.y < 0.0f) throw std::invalid_argument("extrusion radii must be >= 0");
        const float theta = -kTwoPi * v;
        const float c = std::cos(theta), sn = std::sin(theta);
        SurfacePoint p;
        p.position = spine.position(s) + ab.x * c * f.n + ab.y * sn * f.b;
        const float turn = speed > 0.0f ? (ab.x * c * glm::dot(d2, f.n) + ab.y * sn * glm::dot(d2, f.b)) / speed : 0.0f;
        p.dpdu = d1 + dab.x * c * f.n + dab.y * sn * f.b - turn * f.t;
        p.dpdv = kTwoPi * (ab.x * sn * f.n - ab.y * c * f.b);
        p.normal = glm::cross(p.dpdu, p.dpdv);
        // Where the profile shrinks to a point the cross product vanishes: the surface there
        // faces along the spine, backwards at the start and forwards at the end.
        if (!(glm::length(p.normal) > 1e-12f)) p.normal = s < 0.5f ? -f.t : f.t;
        return p;
    };
    return tessellate(surface, along, around);
}

}  // namespace tessera::geometry
