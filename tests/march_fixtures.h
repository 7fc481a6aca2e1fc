// What the march tests share: the exact ray-sphere distance to check marches against, and the
// compute-pass tests' scene, a unit sphere at the origin seen from a camera four units away.
#pragma once
#include <glm/glm.hpp>

#include <cmath>

#include "raster/core/camera.h"
#include "raster/march/march_surface.h"
#include "raster/march/sphere_field.h"
#include "raster/march/surface_pass.h"

namespace tessera::test {

inline Camera march_camera(int width, int height) {
    Camera c;
    c.eye = {0.4f, 0.3f, 4.0f};
    c.lookat = {0.0f, 0.0f, 0.0f};
    c.aspect = float(width) / float(height);
    c.near = 0.5f;
    c.far = 20.0f;
    return c;
}

inline const march::SphereField kUnitSphere{{0.0f, 0.0f, 0.0f}, 1.0f};

// The nearer intersection of the ray o + t d (|d| = 1) with the sphere (c, r), infinity for a
// miss, in double: t = -b - sqrt(b^2 - (|o - c|^2 - r^2)) with b = d.(o - c).
inline double sphere_distance(glm::dvec3 o, glm::dvec3 d, glm::dvec3 c, double r) {
    const glm::dvec3 oc = o - c;
    const double b = glm::dot(d, oc);
    const double disc = b * b - (glm::dot(oc, oc) - r * r);
    return disc < 0.0 ? INFINITY : -b - std::sqrt(disc);
}

inline double unit_sphere_distance(glm::vec3 o, glm::vec3 d) {
    return sphere_distance(glm::dvec3(o), glm::dvec3(d), glm::dvec3(kUnitSphere.centre), 1.0);
}

// The sphere as a marched surface in its bounding slab, with a tolerance tight enough for the
// tests' depth comparisons. Keeps references to `rays` and `background`.
inline march::SurfacePass<march::SlabSurface<march::SphereField>> sphere_pass(const march::RayGenerator& rays,
                                                                              const scene::Background& background) {
    march::MarchSettings settings;
    settings.tolerance = 1e-5f;
    return {march::SlabSurface<march::SphereField>{kUnitSphere, march::Slab{-1.0f, 1.0f}}, rays, settings,
            march::SurfaceLook{}, background};
}

}  // namespace tessera::test
