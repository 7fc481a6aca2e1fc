// The extruded surface of the writhing snakes: an elliptical profile
// swept along a spine curve C(s),
//     r(s, v) = C(s) + a(s) cos(theta) N(s) + b(s) sin(theta) B(s),   theta = -2 pi v,
// where (T, N, B) is a rotation-minimising frame (no twist as the spine bends; computed by the
// double-reflection method of Wang, Juettler, Zheng and Liu, ACM TOG 2008), N starting as the
// world up direction projected off the tangent, and (a, b) the semi-axes along N and B.
//
// The normal is analytic, n = dr/ds x dr/dv. For a rotation-minimising frame the frame turns
// only about axes perpendicular to T, dN/ds = -(C''.N / |C'|) T and dB/ds = -(C''.B / |C'|) T,
// which gives
//     dr/ds = C' + a' cos N + b' sin B - (a cos C''.N + b sin C''.B) / |C'| T,
//     dr/dv = 2 pi (a sin N - b cos B),
// exact up to the frame's own discretisation. uv = (s, v): along the body, around it.
#pragma once
#include <glm/glm.hpp>

#include "raster/geometry/bezier.h"
#include "raster/core/mesh.h"

namespace tessera::geometry {

// Tessellates the sweep with `along` x `around` quads (tessellate()'s grid and winding, in
// parallel). `radii` gives (a, b) over the same s in [0, 1]; radii may reach 0 (a pointed tail;
// the normal there falls back to the spine direction). Throws std::invalid_argument for bad
// counts or negative radii.
Mesh extrude(const BezierCurve<glm::vec3>& spine, const BezierCurve<glm::vec2>& radii, int along,
             int around);

}  // namespace tessera::geometry
