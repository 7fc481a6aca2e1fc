#include "raster/march/metaball_field.h"

#include <algorithm>
#include <span>
#include <cmath>
#include <stdexcept>
#include <string>

#include "raster/march/bounds.h"
#include "raster/march/metaball_packet.h"
#include "raster/simd/lane_math.h"

namespace tessera::march {

namespace {

bool finite(glm::vec3 v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// One ball's kernel sample at p (shared by value and gradient so both read the same K); the
// sum of squares in the order values() uses.
template <class Kernel>
KernelSample<float> sample(const Kernel& kernel, glm::vec3 q, float inv_r2) {
    return kernel.at((q.x * q.x + q.y * q.y + q.z * q.z) * inv_r2);
}

// The same through the style's kernel, picked at run time.
KernelSample<float> sample(MetaballKernel kind, const BlinnKernel& blinn, glm::vec3 q, float inv_r2) {
    switch (kind) {
    case MetaballKernel::wyvill: return sample(WyvillKernel{}, q, inv_r2);
    case MetaballKernel::perlin: return sample(PerlinKernel{}, q, inv_r2);
    default: return sample(blinn, q, inv_r2);
    }
}

}  // namespace

MetaballField::MetaballField(const std::vector<Metaball>& balls, const MetaballStyle& style)
    : style_(style), blinn_(style.blinn_sharpness) {
    if (!(style.threshold > 0.0f) || !std::isfinite(style.threshold))
        throw std::invalid_argument("metaballs: threshold must be positive and finite, got " +
                                    std::to_string(style.threshold));
    if (!(style.blinn_sharpness > 0.0f) || !std::isfinite(style.blinn_sharpness))
        throw std::invalid_argument("metaballs: Blinn sharpness must be positive and finite, got " +
                                    std::to_string(style.blinn_sharpness));
    for (size_t i = 0; i < balls.size(); ++i) {
        const Metaball& b = balls[i];
        if (!finite(b.centre) || !std::isfinite(b.weight))
            throw std::invalid_argument("metaballs: ball " + std::to_string(i) +
                                        " has a non-finite centre or weight");
        if (!(b.radius > 0.0f) || !std::isfinite(b.radius))
            throw std::invalid_argument("metaballs: ball " + std::to_string(i) +
                                        " needs a positive finite radius, got " +
                                        std::to_string(b.radius));
        cx_.push_back(b.centre.x);
        cy_.push_back(b.centre.y);
        cz_.push_back(b.centre.z);
        radius_.push_back(b.radius);
        inv_r2_.push_back(1.0f / (b.radius * b.radius));
        weight_.push_back(b.weight);
    }
}

float MetaballField::value(glm::vec3 p) const {
    float sum = 0.0f;
    for (size_t i = 0; i < cx_.size(); ++i) {
        const glm::vec3 q = p - glm::vec3(cx_[i], cy_[i], cz_[i]);
        const KernelSample<float> k = sample(style_.kernel, blinn_, q, inv_r2_[i]);
        sum += weight_[i] * k.value;
    }
    return sum - style_.threshold;
}

glm::vec3 MetaballField::gradient(glm::vec3 p) const {
    glm::vec3 g(0.0f);
    for (size_t i = 0; i < cx_.size(); ++i) {
        const glm::vec3 q = p - glm::vec3(cx_[i], cy_[i], cz_[i]);
        const KernelSample<float> k = sample(style_.kernel, blinn_, q, inv_r2_[i]);
        g += (weight_[i] * k.d_ds * 2.0f * inv_r2_[i]) * q;
    }
    return g;
}

template <class Kernel>
void MetaballField::accumulate(const Kernel& kernel, const float* x, const float* y,
                               const float* z, float* sum) const {
    // One vfloat of points against one ball at a time, through the kernel's vfloat
    // instantiation: the same operations in the same order as value() per lane.
    using simd::vfloat;
    const vfloat px = vfloat::load(x), py = vfloat::load(y), pz = vfloat::load(z);
    vfloat acc = vfloat::load(sum);
    for (size_t b = 0; b < cx_.size(); ++b) {
        const vfloat qx = px - vfloat(cx_[b]), qy = py - vfloat(cy_[b]), qz = pz - vfloat(cz_[b]);
        const vfloat s = (qx * qx + qy * qy + qz * qz) * vfloat(inv_r2_[b]);
        acc = acc + vfloat(weight_[b]) * kernel.at(s).value;
    }
    acc.store(sum);
}

void MetaballField::values(const float* x, const float* y, const float* z, float* out) const {
    alignas(64) float sum[kMarchLanes] = {};
    switch (style_.kernel) {
    case MetaballKernel::wyvill: accumulate(WyvillKernel{}, x, y, z, sum); break;
    case MetaballKernel::perlin: accumulate(PerlinKernel{}, x, y, z, sum); break;
    default: accumulate(blinn_, x, y, z, sum); break;
    }
    for (int i = 0; i < kMarchLanes; ++i) out[i] = sum[i] - style_.threshold;
}

template <class Kernel>
void MetaballField::accumulate_gradient(const Kernel& kernel, const float* x, const float* y, const float* z,
                                        float* gx, float* gy, float* gz) const {
    // gradient() per lane: g += (w dK/ds 2 / R^2) (p - c), ball by ball.
    using simd::vfloat;
    const vfloat px = vfloat::load(x), py = vfloat::load(y), pz = vfloat::load(z);
    vfloat ax(0.0f), ay(0.0f), az(0.0f);
    for (size_t b = 0; b < cx_.size(); ++b) {
        const vfloat qx = px - vfloat(cx_[b]), qy = py - vfloat(cy_[b]), qz = pz - vfloat(cz_[b]);
        const KernelSample<vfloat> k = kernel.at((qx * qx + qy * qy + qz * qz) * vfloat(inv_r2_[b]));
        const vfloat scale = vfloat(weight_[b]) * k.d_ds * vfloat(2.0f) * vfloat(inv_r2_[b]);
        ax = ax + scale * qx;
        ay = ay + scale * qy;
        az = az + scale * qz;
    }
    ax.store(gx);
    ay.store(gy);
    az.store(gz);
}

void MetaballField::gradients(const float* x, const float* y, const float* z, float* gx, float* gy,
                              float* gz) const {
    switch (style_.kernel) {
    case MetaballKernel::wyvill: accumulate_gradient(WyvillKernel{}, x, y, z, gx, gy, gz); break;
    case MetaballKernel::perlin: accumulate_gradient(PerlinKernel{}, x, y, z, gx, gy, gz); break;
    default: accumulate_gradient(blinn_, x, y, z, gx, gy, gz); break;
    }
}

Interval MetaballField::bounds(glm::vec3 o, glm::vec3 d, float t_far) const {
    Interval hull;  // empty
    for (size_t b = 0; b < cx_.size(); ++b) {
        const Interval s = sphere_interval(o, d, {cx_[b], cy_[b], cz_[b]}, radius_[b], t_far);
        if (s.empty()) continue;
        hull = hull.empty() ? s : Interval{std::min(hull.t0, s.t0), std::max(hull.t1, s.t1)};
    }
    return hull;
}

namespace {

// The cone from the eye that contains a tile's rays (their directions all lie in the cone of
// its corner pixels' directions, since a pixel's unnormalised direction is linear in its
// position), so one test per ball rejects balls nowhere near the tile before any per-ray
// test. `valid` is false when the cone is too wide for the test.
struct RayCone {
    bool valid = false;
    glm::vec3 apex{0.0f}, axis{0.0f};
    float cos_half = 1.0f, sin_half = 0.0f;  // of the half opening angle
};

RayCone cone_around(glm::vec3 apex, std::span<const glm::vec3> directions) {
    RayCone cone;
    glm::vec3 sum(0.0f);
    for (const glm::vec3& d : directions) sum += d;
    const float len = glm::length(sum);
    if (!(len > 0.0f)) return cone;
    cone.axis = sum / len;
    float cos_half = 1.0f;
    for (const glm::vec3& d : directions) cos_half = std::min(cos_half, glm::dot(d, cone.axis));
    cone.apex = apex;
    // Widened by e = 1e-3 rad so rounding never rejects a ball a ray touches (a false "maybe"
    // only costs the per-ray tests that follow), through cos(h + e) = cos h cos e - sin h sin e
    // and sin(h + e) = sin h cos e + cos h sin e.
    const float c = std::clamp(cos_half, -1.0f, 1.0f), s = std::sqrt(1.0f - c * c);
    constexpr float kCosE = 0.9999995f, kSinE = 9.9999983e-4f;  // cos 1e-3, sin 1e-3
    cone.cos_half = c * kCosE - s * kSinE;
    cone.sin_half = s * kCosE + c * kSinE;
    // A very wide cone (half angle 1.5 rad or more): the test below would not hold.
    cone.valid = cone.cos_half > 0.0707372f;  // cos 1.5
    return cone;
}

// True unless the sphere lies entirely outside the cone: the angle between the axis and the
// centre must not exceed the half angle plus the sphere's angular radius b (sin b = R/dist),
// compared through cosines, cos(half + b) = cos half cos b - sin half sin b, with no
// inverse trigonometry per ball.
bool cone_may_touch(const RayCone& cone, glm::vec3 centre, float radius) {
    if (!cone.valid) return true;
    const glm::vec3 v = centre - cone.apex;
    const float dist = glm::length(v);
    if (dist <= radius) return true;
    const float sin_b = radius / dist;
    const float cos_b = std::sqrt(1.0f - sin_b * sin_b);
    const float cos_limit = cone.cos_half * cos_b - cone.sin_half * sin_b;
    // half + b >= pi/2 happens only for a huge sphere close by: accept it.
    if (cos_limit <= 0.0f) return true;
    return glm::dot(v, cone.axis) >= cos_limit * dist;
}

}  // namespace

void MetaballField::begin_subset(MetaballField& subset) const {
    subset.style_ = style_;
    subset.blinn_ = blinn_;
    for (auto* v : {&subset.cx_, &subset.cy_, &subset.cz_, &subset.radius_, &subset.inv_r2_, &subset.weight_})
        v->clear();
}

void MetaballField::copy_ball(size_t b, MetaballField& subset) const {
    subset.cx_.push_back(cx_[b]);
    subset.cy_.push_back(cy_[b]);
    subset.cz_.push_back(cz_[b]);
    subset.radius_.push_back(radius_[b]);
    subset.inv_r2_.push_back(inv_r2_[b]);
    subset.weight_.push_back(weight_[b]);
}

void MetaballField::cull(glm::vec3 eye, std::span<const glm::vec3> corners, MetaballField& subset) const {
    begin_subset(subset);
    const RayCone cone = cone_around(eye, corners);
    for (size_t b = 0; b < cx_.size(); ++b) {
        if (!cone_may_touch(cone, {cx_[b], cy_[b], cz_[b]}, radius_[b])) continue;
        copy_ball(b, subset);
    }
}

void MetaballField::cull(const RayPacket& rays, float t_far, MetaballPacket& packet,
                         PacketSegments& segments) const {
    using simd::std_max;
    using simd::std_min;
    using simd::vfloat;
    using simd::vmask;
    MetaballField& subset = packet.field_;
    begin_subset(subset);
    packet.centre_norm_.clear();
    packet.positive_weight_.clear();
    packet.closest_.clear();
    packet.miss2_.clear();
    const vfloat ox = vfloat::load(rays.ox), oy = vfloat::load(rays.oy), oz = vfloat::load(rays.oz);
    const vfloat dx = vfloat::load(rays.dx), dy = vfloat::load(rays.dy), dz = vfloat::load(rays.dz);
    const vmask live = simd::lane_index() < simd::vint(rays.count);
    vfloat hull0(Interval{}.t0), hull1(Interval{}.t1);  // empty
    float magnitude = style_.threshold;
    for (size_t b = 0; b < cx_.size(); ++b) {
        const glm::vec3 c(cx_[b], cy_[b], cz_[b]);
        // sphere_interval in lanes, with its operations in its order (glm::dot sums x, y, z;
        // std::max and std::min as std_max and std_min), so the intervals are its bits.
        const vfloat ocx = ox - vfloat(c.x), ocy = oy - vfloat(c.y), ocz = oz - vfloat(c.z);
        const vfloat along = (dx * ocx + dy * ocy) + dz * ocz;
        const vfloat px = ocx - along * dx, py = ocy - along * dy, pz = ocz - along * dz;
        const vfloat miss2 = (px * px + py * py) + pz * pz;
        const vfloat disc = vfloat(radius_[b] * radius_[b]) - miss2;
        const vfloat root = simd::sqrt(disc);
        const vfloat closest = along * vfloat(-1.0f);  // -along, sign of zero included
        const vfloat s0 = std_max(closest - root, vfloat(0.0f));
        const vfloat s1 = std_min(closest + root, vfloat(t_far));
        const vmask crosses = simd::andnot(disc < vfloat(0.0f), live & (s0 <= s1));
        if (!simd::any(crosses)) continue;
        const vmask first = simd::andnot(hull0 <= hull1, crosses);
        hull0 = simd::select(crosses, simd::select(first, s0, std_min(hull0, s0)), hull0);
        hull1 = simd::select(crosses, simd::select(first, s1, std_max(hull1, s1)), hull1);
        copy_ball(b, subset);
        packet.centre_norm_.push_back(glm::length(c));
        packet.positive_weight_.push_back(std::max(weight_[b], 0.0f));
        packet.closest_.emplace_back();
        packet.miss2_.emplace_back();
        closest.store(packet.closest_.back().v);
        miss2.store(packet.miss2_.back().v);
        magnitude += std::abs(weight_[b]);
    }
    hull0.store(segments.t0);
    hull1.store(segments.t1);
    simd::sqrt((ox * ox + oy * oy) + oz * oz).store(packet.origin_norm_.v);
    packet.reach_ = style_.threshold - 1e-5f * magnitude;
}

}  // namespace tessera::march
