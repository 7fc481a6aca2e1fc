#include "raster/pipeline/triangle_setup.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace tessera::pipeline {

WindowVertex project_and_snap(const Viewport& viewport, const glm::vec4& clip) {
    float wx, wy, wz;
    viewport.to_window(clip.x, clip.y, clip.z, clip.w, wx, wy, wz);
    const float sub = float(kSubpixels);
    return {int32_t(std::nearbyint(wx * sub)), int32_t(std::nearbyint(wy * sub)), wz};
}

DepthPlane DepthPlane::from(const WindowVertex& v0, const WindowVertex& v1, const WindowVertex& v2) {
    DepthPlane p;
    p.ax = int16_t(v0.X >> kSubpixelBits);  // the pixel that holds vertex 0 (floor)
    p.ay = int16_t(v0.Y >> kSubpixelBits);
    const int64_t det = int64_t(v1.X - v0.X) * (v2.Y - v0.Y) - int64_t(v2.X - v0.X) * (v1.Y - v0.Y);
    if (det == 0) {  // never traversed (zero area), but keep the plane finite
        p.c = float(double(v0.z) - 1.0);
        return p;
    }
    // The anchor pixel's centre, relative to vertex 0 (exact in double).
    const double cx = (double(p.ax) + 0.5) - double(v0.X) / kSubpixels;
    const double cy = (double(p.ay) + 0.5) - double(v0.Y) / kSubpixels;
    depth_plane_coefficients(v1.X - v0.X, v1.Y - v0.Y, v2.X - v0.X, v2.Y - v0.Y, v0.z, v1.z, v2.z, cx, cy, p.a, p.b, p.c);
    return p;
}

float DepthPlane::offset_at(int x, int y) const {
    const float z = std::fma(a, float(x - ax), std::fma(b, float(y - ay), c));
    return std::min(std::max(z, -1.0f), 0.0f);
}

float DepthPlane::offset_at_sample(int x, int y, int ox, int oy) const {
    const float fx = float(x - ax) + float(ox) * (1.0f / 16.0f);
    const float fy = float(y - ay) + float(oy) * (1.0f / 16.0f);
    const float z = std::fma(a, fx, std::fma(b, fy, c));
    return std::min(std::max(z, -1.0f), 0.0f);
}

float DepthPlane::edge_step(int32_t dX, int32_t dY) const {
    // |dX|, |dY| <= 2^23: the squares and their sum are exact in double, and sqrt rounds
    // correctly, so every build computes the same step.
    const double length = std::sqrt(double(dX) * double(dX) + double(dY) * double(dY));
    return float(0x1p-10 * (double(a) * -double(dY) + double(b) * double(dX)) / length);
}

namespace {

// F_i at pixel (x, y), from the setup's value at (minx, miny); exact in int64.
int64_t edge_at(const TriangleSetup& t, int i, int x, int y) {
    return t.f[i] + int64_t(t.dx[i]) * (y - t.miny) - int64_t(t.dy[i]) * (x - t.minx);
}

// Whether dX y - dY x = -K / 256 has integer solutions, for K a multiple of 256.
bool line_meets_centres(int32_t dX, int32_t dY, int64_t k_over_256) {
    const int64_t g = std::gcd(int64_t(dX), int64_t(dY));
    return g != 0 && k_over_256 % g == 0;
}

}  // namespace

bool holds_sample(const TriangleSetup& t, int i, int ox, int oy) {
    if (!is_top_left(t.dx[i], t.dy[i])) return false;
    const int64_t k = sample_step(t, i, ox, oy);
    if ((k & (kSubpixels - 1)) != 0) return false;
    // K >> 8 from F at the box corner (setup_triangle), then the sample's whole part.
    const int64_t whole = t.f[i] - int64_t(t.dx[i]) * t.miny + int64_t(t.dy[i]) * t.minx + (k >> kSubpixelBits);
    return line_meets_centres(t.dx[i], t.dy[i], whole);
}

float depth_offset(const TriangleSetup& t, int x, int y) {
    float z = std::fma(t.depth.a, float(x - t.depth.ax), std::fma(t.depth.b, float(y - t.depth.ay), t.depth.c));
    for (int i = 0; i < 3; ++i)
        if (holds_centres(t, i) && edge_at(t, i, x, y) == 0) z = z + t.depth.edge_step(t.dx[i], t.dy[i]);
    return std::min(std::max(z, -1.0f), 0.0f);
}

float depth_offset_at_sample(const TriangleSetup& t, int x, int y, int ox, int oy) {
    const float fx = float(x - t.depth.ax) + float(ox) * (1.0f / 16.0f);
    const float fy = float(y - t.depth.ay) + float(oy) * (1.0f / 16.0f);
    float z = std::fma(t.depth.a, fx, std::fma(t.depth.b, fy, t.depth.c));
    for (int i = 0; i < 3; ++i)
        if (holds_sample(t, i, ox, oy) && edge_at(t, i, x, y) + sample_offset(t, i, ox, oy) == 0)
            z = z + t.depth.edge_step(t.dx[i], t.dy[i]);
    return std::min(std::max(z, -1.0f), 0.0f);
}

SetupResult setup_triangle(const WindowVertex& v0, const WindowVertex& v1_in,
                           const WindowVertex& v2_in, CullMode cull, const Viewport& viewport,
                           TriangleSetup& out, int samples) {
    WindowVertex v1 = v1_in, v2 = v2_in;
    // Twice the signed area in sub-pixels^2 (fixed_point.h: |.| <= 2^47).
    const int64_t area2 = int64_t(v1.X - v0.X) * (v2.Y - v0.Y) - int64_t(v1.Y - v0.Y) * (v2.X - v0.X);
    if (area2 == 0) return SetupResult::zero_area;
    // Window y runs down, so a counter-clockwise (front) triangle in NDC has area2 < 0.
    const bool front = area2 < 0;
    if ((cull == CullMode::back && !front) || (cull == CullMode::front && front))
        return SetupResult::culled_face;
    if (area2 < 0) std::swap(v1, v2);  // inside: all edge functions positive

    const int32_t xmin = std::min(v0.X, std::min(v1.X, v2.X)), xmax = std::max(v0.X, std::max(v1.X, v2.X));
    const int32_t ymin = std::min(v0.Y, std::min(v1.Y, v2.Y)), ymax = std::max(v0.Y, std::max(v1.Y, v2.Y));
    // Pixels whose centre 256x + 128 lies within [xmin, xmax]; with several samples, pixels
    // with a sample position 256x + 128 + 16o, o in [-8, 7], that may.
    const int32_t lo = samples > 1 ? 0 : kSubpixels / 2 - 1, hi = samples > 1 ? 0 : kSubpixels / 2;
    const int32_t minx = std::max((xmin + lo) >> kSubpixelBits, 0);
    const int32_t maxx = std::min((xmax - hi) >> kSubpixelBits, viewport.width - 1);
    const int32_t miny = std::max((ymin + lo) >> kSubpixelBits, 0);
    const int32_t maxy = std::min((ymax - hi) >> kSubpixelBits, viewport.height - 1);
    if (minx > maxx || miny > maxy) return SetupResult::no_samples;

    // E(P) = dX*(Py - Ya) - dY*(Px - Xa) at P = (256x + 128, 256y + 128) equals
    // 256*(dX*y - dY*x) + K. Inside: E > 0, or E == 0 on a top/left edge, i.e.
    // E - 1 + tl >= 0, i.e. (dX*y - dY*x) + floor((K - 1 + tl) / 256) >= 0 (>> floors).
    unsigned on_edge = 0;  // TriangleSetup::on_edge
    auto edge = [&](int i, const WindowVertex& a, const WindowVertex& b) {
        const int32_t dX = b.X - a.X, dY = b.Y - a.Y;
        const int64_t K = int64_t(dX) * (kSubpixels / 2 - a.Y) - int64_t(dY) * (kSubpixels / 2 - a.X) -
                          (is_top_left(dX, dY) ? 0 : 1);
        out.f[i] = int64_t(dX) * miny - int64_t(dY) * minx + (K >> kSubpixelBits);
        out.residue[i] = uint8_t(K & (kSubpixels - 1));
        // holds_centres(): a top-left edge (K is then E's constant part, no bias) whose line
        // meets the centres' lattice: along a row or column, when that row or column is one
        // of centres; otherwise by Bezout.
        if ((K & (kSubpixels - 1)) == 0 && is_top_left(dX, dY)) {
            const bool meets = dY == 0   ? (a.Y & (kSubpixels - 1)) == kSubpixels / 2
                               : dX == 0 ? (a.X & (kSubpixels - 1)) == kSubpixels / 2
                                         : line_meets_centres(dX, dY, K >> kSubpixelBits);
            on_edge |= unsigned(meets) << i;
        }
        out.dx[i] = dX;
        out.dy[i] = dY;
    };
    edge(0, v0, v1);
    edge(1, v1, v2);
    edge(2, v2, v0);
    out.depth = DepthPlane::from(v0, v1, v2);
    out.minx = int16_t(minx);
    out.miny = int16_t(miny);
    out.maxx = int16_t(maxx);
    out.maxy = int16_t(maxy);
    out.small = (xmax - xmin) < kSmallExtent && (ymax - ymin) < kSmallExtent;
    out.transparent = 0;
    out.on_edge = uint8_t(on_edge);
    return SetupResult::drawn;
}

}  // namespace tessera::pipeline
