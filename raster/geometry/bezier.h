// Piecewise cubic Bezier curves over a global parameter s in [0, 1], with exact first and
// second derivatives (d/ds, d^2/ds^2): the spine of an extruded surface (vec3) and the radius
// profile along it (vec2). A curve of K segments maps s to segment k = floor(s K), local
// t = s K - k, so d/ds = K d/dt.
//
// catmull_rom() builds the uniform Catmull-Rom spline through a list of points in this form:
// segment k is the Bezier (p_k, p_k + m_k/3, p_{k+1} - m_{k+1}/3, p_{k+1}) with tangents
// m_k = (p_{k+1} - p_{k-1}) / 2 (the end points repeated), so it passes through every point
// and is C1 — control points can move freely (animated snakes) without kinks.
#pragma once
#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <span>
#include <stdexcept>
#include <vector>

namespace tessera::geometry {

template <class V>
class BezierCurve {
public:
    explicit BezierCurve(std::vector<std::array<V, 4>> segments) : segments_(std::move(segments)) {
        if (segments_.empty()) throw std::invalid_argument("a Bezier curve needs a segment");
    }

    V position(float s) const {
        const auto [b, t] = locate(s);
        const float u = 1.0f - t;
        return u * u * u * b[0] + 3.0f * u * u * t * b[1] + 3.0f * u * t * t * b[2] + t * t * t * b[3];
    }
    V derivative(float s) const {
        const auto [b, t] = locate(s);
        const float u = 1.0f - t;
        const V d = 3.0f * (u * u * (b[1] - b[0]) + 2.0f * u * t * (b[2] - b[1]) + t * t * (b[3] - b[2]));
        return d * float(segments_.size());
    }
    V second_derivative(float s) const {
        const auto [b, t] = locate(s);
        const V d = 6.0f * ((1.0f - t) * (b[2] - 2.0f * b[1] + b[0]) + t * (b[3] - 2.0f * b[2] + b[1]));
        const float k = float(segments_.size());
        return d * (k * k);
    }
    size_t segment_count() const { return segments_.size(); }

private:
    struct Located {
        const std::array<V, 4>& b;
        float t;
    };
    Located locate(float s) const {
        const float k = float(segments_.size());
        const float x = std::isfinite(s) ? std::clamp(s, 0.0f, 1.0f) * k : 0.0f;
        const size_t i = std::min(size_t(x), segments_.size() - 1);
        return {segments_[i], x - float(i)};
    }
    std::vector<std::array<V, 4>> segments_;
};

// Throws std::invalid_argument for fewer than 2 points.
template <class V>
BezierCurve<V> catmull_rom(std::span<const V> points) {
    if (points.size() < 2) throw std::invalid_argument("a Catmull-Rom spline needs 2 points");
    const size_t n = points.size();
    const auto tangent = [&](size_t k) {
        return 0.5f * (points[std::min(k + 1, n - 1)] - points[k == 0 ? 0 : k - 1]);
    };
    std::vector<std::array<V, 4>> segments;
    for (size_t k = 0; k + 1 < n; ++k)
        segments.push_back({points[k], points[k] + tangent(k) / 3.0f,
                            points[k + 1] - tangent(k + 1) / 3.0f, points[k + 1]});
    return BezierCurve<V>(std::move(segments));
}

}  // namespace tessera::geometry
