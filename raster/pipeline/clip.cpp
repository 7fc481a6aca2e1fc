#include "raster/pipeline/clip.h"

#include <cfloat>
#include <cmath>

#include "raster/pipeline/vertex_stage.h"

namespace tessera::pipeline {

namespace {

// Signed distance of v to one clip plane: >= 0 inside.
struct Plane {
    uint32_t bit;
    glm::vec4 coefficients;  // dot(coefficients, v) >= 0 inside
};

int clip_against(const Plane& plane, const glm::vec4* in, int count, glm::vec4* out) {
    int n = 0;
    for (int i = 0; i < count; ++i) {
        const glm::vec4& a = in[i];
        const glm::vec4& b = in[(i + 1) % count];
        const float da = glm::dot(plane.coefficients, a);
        const float db = glm::dot(plane.coefficients, b);
        if (da >= 0.0f) out[n++] = a;
        if ((da >= 0.0f) != (db >= 0.0f)) {
            // Parameter where the interpolated coordinate meets the plane, always computed
            // from the inside vertex so a shared edge is cut at the same point in both of the
            // triangles that share it.
            if (da >= 0.0f) {
                const float t = da / (da - db);
                out[n++] = a + t * (b - a);
            } else {
                const float t = db / (db - da);
                out[n++] = b + t * (a - b);
            }
        }
    }
    return n;
}

}  // namespace

int clip_triangle(const glm::vec4 in[3], uint32_t codes, const Viewport& viewport,
                  glm::vec4 out[kMaxClippedVertices]) {
    const float gx = viewport.guard_x, gy = viewport.guard_y;
    const Plane planes[] = {
        {kClipNear, {0.0f, 0.0f, 1.0f, 1.0f}},    // z + w >= 0
        {kClipFar, {0.0f, 0.0f, -1.0f, 1.0f}},    // w - z >= 0
        {kClipLeft, {1.0f, 0.0f, 0.0f, gx}},      // x + gx*w >= 0
        {kClipRight, {-1.0f, 0.0f, 0.0f, gx}},    // gx*w - x >= 0
        {kClipTop, {0.0f, -1.0f, 0.0f, gy}},      // gy*w - y >= 0
        {kClipBottom, {0.0f, 1.0f, 0.0f, gy}},    // y + gy*w >= 0
    };
    glm::vec4 buffer[2][kMaxClippedVertices];
    int count = 3;
    for (int i = 0; i < 3; ++i) buffer[0][i] = in[i];
    int current = 0;
    for (const Plane& plane : planes) {
        if (!(codes & plane.bit)) continue;
        count = clip_against(plane, buffer[current], count, buffer[1 - current]);
        current = 1 - current;
        if (count < 3) return 0;
    }
    for (int i = 0; i < count; ++i) {
        // w > 0 holds after the near cut for any projection whose near plane is in front of
        // the eye; a vertex with w <= 0 left by a degenerate matrix cannot be projected.
        // Extreme but finite inputs (near FLT_MAX) defeat the arithmetic: plane distances
        // overflow (inf - inf = NaN in t) or the cut point lands far off its plane through
        // cancellation, and a w below FLT_MIN overflows 1 / w. Such a polygon is dropped
        // unless every vertex projects inside the guard band, which fixed_point.h's integer
        // ranges rely on (found by tests/fuzz/fuzz_raster.cpp). Both rasterizers clip here.
        const glm::vec4& c = buffer[current][i];
        if (!(c.w >= FLT_MIN)) return 0;
        float wx, wy, wz;
        viewport.to_window(c.x, c.y, c.z, c.w, wx, wy, wz);
        constexpr float kLimit = kCoordLimit * 1.01f;  // rounding slack, still < 2^14
        if (!(std::fabs(wx) <= kLimit && std::fabs(wy) <= kLimit && std::isfinite(wz))) return 0;
        out[i] = buffer[current][i];
    }
    return count;
}

}  // namespace tessera::pipeline
