// Tessellated geometry: analytic normals against finite differences of r(u, v), winding,
// counts, heightfields and the extruded snake body.
#include <gtest/gtest.h>

#include <glm/gtc/constants.hpp>

#include <tbb/global_control.h>

#include <vector>

#include "raster/geometry/box.h"
#include "raster/geometry/extrusion.h"
#include "raster/geometry/param_surface.h"
#include "raster/geometry/surfaces.h"

using namespace tessera;

namespace {

// Angle (radians) between the analytic normal and the cross product of central differences.
float normal_error(const geometry::SurfaceFunction& r, float u, float v) {
    const float h = 1e-3f;
    const glm::vec3 du = (r(u + h, v).position - r(u - h, v).position) / (2.0f * h);
    const glm::vec3 dv = (r(u, v + h).position - r(u, v - h).position) / (2.0f * h);
    const glm::vec3 fd = glm::normalize(glm::cross(du, dv));
    const glm::vec3 n = glm::normalize(r(u, v).normal);
    return std::acos(std::clamp(std::abs(glm::dot(fd, n)), 0.0f, 1.0f));
}

// Also checks the analytic partials themselves.
void expect_surface_consistent(const geometry::SurfaceFunction& r, const char* name) {
    for (float u : {0.13f, 0.37f, 0.61f, 0.89f})
        for (float v : {0.21f, 0.5f, 0.77f}) {
            EXPECT_LT(normal_error(r, u, v), 2e-3f) << name << " at " << u << ", " << v;
            const float h = 1e-3f;
            const glm::vec3 du = (r(u + h, v).position - r(u - h, v).position) / (2.0f * h);
            EXPECT_LT(glm::length(du - r(u, v).dpdu), 2e-2f * std::max(1.0f, glm::length(du))) << name;
            const glm::vec3 dv = (r(u, v + h).position - r(u, v - h).position) / (2.0f * h);
            EXPECT_LT(glm::length(dv - r(u, v).dpdv), 2e-2f * std::max(1.0f, glm::length(dv))) << name;
        }
}

// Every triangle is counter-clockwise seen from the side its vertex normals point to.
void expect_winding_follows_normals(const Mesh& m, const char* name) {
    int wrong = 0;
    for (size_t t = 0; t < m.triangle_count(); ++t) {
        const uint32_t a = m.indices[3 * t], b = m.indices[3 * t + 1], c = m.indices[3 * t + 2];
        const glm::vec3 face = glm::cross(m.positions[b] - m.positions[a], m.positions[c] - m.positions[a]);
        if (glm::length(face) < 1e-6f) continue;  // collapsed at a pole (up to rounding)
        wrong += glm::dot(face, m.normals[a] + m.normals[b] + m.normals[c]) < 0.0f;
    }
    EXPECT_EQ(wrong, 0) << name;
}

}  // namespace

TEST(SceneGeometry, SurfaceNormalsMatchFiniteDifferences) {
    expect_surface_consistent(geometry::sphere_surface({1, 2, 3}, 1.5f), "sphere");
    expect_surface_consistent(geometry::ellipsoid_surface({0, 0, 0}, {2.0f, 0.5f, 1.0f}), "ellipsoid");
    expect_surface_consistent(geometry::torus_surface(2.0f, 0.5f), "torus");
    expect_surface_consistent(geometry::flag_surface(3.0f, 2.0f, 0.2f, 2.0f, 0.7f), "flag");
}

TEST(SceneGeometry, SphereNormalIsTheClosedForm) {
    const auto r = geometry::sphere_surface({0, 0, 0}, 2.0f);
    const float u = 0.3f, v = 0.4f, pi = glm::pi<float>();
    const glm::vec3 seed(std::cos(2 * pi * u) * std::sin(pi * v), std::sin(2 * pi * u) * std::sin(pi * v),
                         std::cos(pi * v));
    EXPECT_LT(glm::length(glm::normalize(r(u, v).normal) - seed), 1e-6f);
    EXPECT_LT(glm::length(r(u, v).position - 2.0f * seed), 1e-5f);
}

TEST(SceneGeometry, TessellationCountsUvAndWinding) {
    const Mesh m = geometry::tessellate(geometry::sphere_surface({0, 0, 0}, 1.0f), 16, 8);
    EXPECT_EQ(m.vertex_count(), 17u * 9u);
    EXPECT_EQ(m.triangle_count(), 2u * 16u * 8u);
    EXPECT_EQ(m.uvs[9 * 16 + 8], glm::vec2(1.0f, 1.0f));
    for (const glm::vec3& n : m.normals) EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
    expect_winding_follows_normals(m, "sphere");
    expect_winding_follows_normals(geometry::tessellate(geometry::flag_surface(2, 1, 0.3f, 3, 0), 30, 10), "flag");
    expect_winding_follows_normals(geometry::tessellate(geometry::torus_surface(1.0f, 0.3f), 24, 12), "torus");
    EXPECT_THROW(geometry::tessellate(geometry::sphere_surface({0, 0, 0}, 1.0f), 0, 4), std::invalid_argument);
}

TEST(SceneGeometry, TessellationIsIndependentOfThreadCount) {
    const auto surface = geometry::torus_surface(1.0f, 0.4f);
    Mesh one;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = geometry::tessellate(surface, 64, 32);
    }
    const Mesh many = geometry::tessellate(surface, 64, 32);
    EXPECT_EQ(one.positions, many.positions);
    EXPECT_EQ(one.normals, many.normals);
    EXPECT_EQ(one.indices, many.indices);
}

TEST(SceneGeometry, FlatHeightfieldFacesUpAndSlopesTilt) {
    std::vector<float> flat(5 * 4, 0.25f);
    const Mesh m = geometry::tessellate(geometry::heightfield_surface(flat, 5, 4, {4.0f, 3.0f}, 2.0f), 4, 3);
    ASSERT_EQ(m.vertex_count(), 20u);
    for (size_t i = 0; i < m.vertex_count(); ++i) {
        EXPECT_NEAR(m.positions[i].y, 0.5f, 1e-6f);
        EXPECT_LT(glm::length(m.normals[i] - glm::vec3(0, 1, 0)), 1e-6f);
    }
    expect_winding_follows_normals(m, "heightfield");
    // h = x along the columns: slope 1 per sample over 1 unit per sample -> n ~ (-1, 1, 0).
    std::vector<float> ramp(5 * 4);
    for (int z = 0; z < 4; ++z)
        for (int x = 0; x < 5; ++x) ramp[size_t(z * 5 + x)] = float(x);
    const Mesh r = geometry::tessellate(geometry::heightfield_surface(ramp, 5, 4, {4.0f, 3.0f}, 1.0f), 4, 3);
    EXPECT_LT(glm::length(r.normals[7] - glm::normalize(glm::vec3(-1, 1, 0))), 1e-5f);
    EXPECT_THROW(geometry::heightfield_surface(ramp, 4, 4, {1, 1}, 1), std::invalid_argument);
}

TEST(SceneGeometry, ExtrudedBodyNormalsMatchTheMeshShape) {
    // Gentle bends: the radius of curvature stays above the tube radius (no self-overlap).
    const std::vector<glm::vec3> spine_points = {{0, 0, 0}, {1, 0.1f, 0.2f}, {2, 0, -0.2f}, {3, 0.1f, 0.15f}, {4, 0, 0}};
    const std::vector<glm::vec2> radii = {{0.1f, 0.15f}, {0.12f, 0.18f}, {0.1f, 0.15f}, {0.05f, 0.08f}, {0.0f, 0.0f}};
    const int along = 400, around = 48;
    const Mesh m = geometry::extrude(geometry::catmull_rom<glm::vec3>(spine_points), geometry::catmull_rom<glm::vec2>(radii), along, around);
    ASSERT_EQ(m.vertex_count(), size_t(along + 1) * size_t(around + 1));
    expect_winding_follows_normals(m, "extrusion");
    // Interior vertices: the analytic normal against the cross product of grid differences.
    const auto at = [&](int i, int j) { return m.positions[size_t(i) * (around + 1) + size_t(j)]; };
    float worst = 0.0f;
    for (int i = 20; i < along - 60; i += 7)
        for (int j = 1; j < around; j += 5) {
            const glm::vec3 fd = glm::normalize(glm::cross(at(i + 1, j) - at(i - 1, j), at(i, j + 1) - at(i, j - 1)));
            const glm::vec3 n = m.normals[size_t(i) * (around + 1) + size_t(j)];
            worst = std::max(worst, std::acos(std::clamp(glm::dot(fd, n), -1.0f, 1.0f)));
        }
    EXPECT_LT(worst, 0.05f);  // radians; grid differences are second-order accurate
    // The body passes through the spine points' neighbourhood: ring centres follow the spine.
    glm::vec3 centre(0.0f);
    for (int j = 0; j < around; ++j) centre += at(along / 2, j);
    EXPECT_LT(glm::length(centre / float(around) - geometry::catmull_rom<glm::vec3>(spine_points).position(0.5f)), 0.02f);
}

TEST(SceneGeometry, CatmullRomPassesThroughItsPointsWithExactDerivatives) {
    const std::vector<glm::vec3> p = {{0, 0, 0}, {1, 2, 0}, {3, 1, 1}, {4, 0, 2}};
    const auto c = geometry::catmull_rom<glm::vec3>(p);
    for (size_t k = 0; k < p.size(); ++k) EXPECT_LT(glm::length(c.position(float(k) / 3.0f) - p[k]), 1e-5f);
    const float s = 0.41f, h = 1e-3f;
    EXPECT_LT(glm::length((c.position(s + h) - c.position(s - h)) / (2 * h) - c.derivative(s)), 2e-2f);
    EXPECT_LT(glm::length((c.derivative(s + h) - c.derivative(s - h)) / (2 * h) - c.second_derivative(s)), 0.2f);
}

TEST(SceneGeometry, BoxFacesPointOutwardWithFullUvSquares) {
    const Mesh m = geometry::box_mesh({1.0f, 2.0f, 0.5f});
    ASSERT_EQ(m.vertex_count(), 24u);
    ASSERT_EQ(m.triangle_count(), 12u);
    expect_winding_follows_normals(m, "box");
    for (size_t i = 0; i < m.vertex_count(); ++i) {
        EXPECT_GT(glm::dot(m.positions[i], m.normals[i]), 0.0f);  // outward
        // uv: u grows along the tangent, so tangent frames from positions and uv agree.
        const size_t face = i / 4 * 4;
        const glm::vec3 along_u = m.positions[face + 1] - m.positions[face];
        EXPECT_GT(glm::dot(along_u, glm::vec3(m.tangents[i])), 0.0f);
        // The tangent (+u direction) lies in the face.
        EXPECT_NEAR(glm::dot(glm::vec3(m.tangents[i]), m.normals[i]), 0.0f, 1e-6f);
    }
    EXPECT_THROW(geometry::box_mesh({1, 0, 1}), std::invalid_argument);
}
