// What the marcher needs from a surface (MarchField): an implicit function with a value and a
// gradient. (procedural::ImplicitField is one family of such fields, with a virtual interface.)
//
// Sign convention: f > 0 inside the solid, f < 0 outside, the surface is f = 0.
// The terrain f(p) = h(p.xz) - p.y, the 3-D noise w/32 + 0.5 - p.y and the metaball sum
// sum K(|p - c|) - T all read this way, so a ray that starts in the air meets the surface at
// its first sign change from - to +, and the outward normal is -grad f / |grad f|.
#pragma once
#include <glm/glm.hpp>

#include <concepts>
#include <cstddef>

#include "raster/march/ray_packet.h"

namespace tessera::march {

template <class F>
concept MarchField = requires(const F& field, glm::vec3 p) {
    { field.value(p) } -> std::convertible_to<float>;
    { field.gradient(p) } -> std::convertible_to<glm::vec3>;
};

// A field that can also evaluate kMarchLanes points at once (structure of arrays), written so
// the lane loop is innermost and vectorises. It must return what value() returns per point.
template <class F>
concept PacketField = MarchField<F> && requires(const F& field, const float* c, float* out) {
    field.values(c, c, c, out);
};

// A field with a batch form over any count of points (the procedural/ fields' interface).
template <class F>
concept BatchField = MarchField<F> && requires(const F& field, const float* c, float* out) {
    field.value_batch(size_t{1}, c, c, c, out);
};

// A packet field that bounds itself along its packet's rays: may_reach(t_from, t_to) is the
// mask of lanes whose ray might meet f >= 0 at a sample with t in [t_from, t_to] (it may keep
// a lane that does not, never drop one that does). march_packet skips the samples no lane
// might need, so a bound changes the work, never the result.
template <class F>
concept BoundedPacketField = PacketField<F> && requires(const F& field, simd::vfloat t) {
    { field.may_reach(t, t) } -> std::same_as<simd::vmask>;
};

// A field whose gradient has a packet form: gradients(x, y, z, gx, gy, gz) writes what
// gradient() returns at each of kMarchLanes points, bit for bit.
template <class F>
concept PacketGradientField = MarchField<F> && requires(const F& field, const float* c, float* out) {
    field.gradients(c, c, c, out, out, out);
};

// A field with a batch form of value and gradient over any count of points (the procedural/
// fields' sample_batch, which gives sample()'s values and gradients bit for bit).
template <class F>
concept SampleBatchField = MarchField<F> && requires(const F& field, const float* c, float* out) {
    field.sample_batch(size_t{1}, c, c, c, out, out, out, out);
};

// Field gradients at kMarchLanes points, equal to gradient() at each: the field's packet or
// batch form where it has one, otherwise one gradient() per lane.
template <MarchField F>
inline void evaluate_gradients(const F& field, const float* x, const float* y, const float* z, float* gx,
                               float* gy, float* gz) {
    if constexpr (PacketGradientField<F>) {
        field.gradients(x, y, z, gx, gy, gz);
    } else if constexpr (SampleBatchField<F>) {
        alignas(64) float value[kMarchLanes];
        field.sample_batch(size_t(kMarchLanes), x, y, z, value, gx, gy, gz);
    } else {
        for (int i = 0; i < kMarchLanes; ++i) {
            const glm::vec3 g = field.gradient(glm::vec3(x[i], y[i], z[i]));
            gx[i] = g.x;
            gy[i] = g.y;
            gz[i] = g.z;
        }
    }
}

// Field values at kMarchLanes points: the field's own packet or batch loop where it has one,
// otherwise one value() per lane.
template <MarchField F>
inline void evaluate_lanes(const F& field, const float* x, const float* y, const float* z,
                           float* out) {
    if constexpr (PacketField<F>) {
        field.values(x, y, z, out);
    } else if constexpr (BatchField<F>) {
        field.value_batch(size_t(kMarchLanes), x, y, z, out);
    } else {
        for (int i = 0; i < kMarchLanes; ++i) out[i] = field.value(glm::vec3(x[i], y[i], z[i]));
    }
}

}  // namespace tessera::march
