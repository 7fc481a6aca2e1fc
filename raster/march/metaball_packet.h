// The metaballs one packet of rays meets (filled by MetaballField::cull): the balls some ray of
// the packet crosses, which the packet marches, and each ray's closest approach to each of
// them, which bounds the field along the ray.
//
// Every kernel falls monotonically from the centre to the support radius (metaball_kernel.h),
// so over a stretch [a, b] of a ray a ball adds at most w K(s_min), s_min the squared distance
// from the stretch to its centre over R^2: with t_c the closest approach's parameter and m^2
// the squared miss distance, dist^2 = m^2 + (clamp(t_c, a, b) - t_c)^2. A stretch where the
// positive weights' sum stays below the threshold holds no sample with f >= 0, and the marcher
// skips its samples (march_packet). The bound is widened so that float rounding can never
// make it tighter than a computed sample: each distance is shortened by 1e-5 of the
// coordinates' magnitude (rounding of o + t d and of p - c is ~1e-7 of it) and the sum must
// stay below the threshold by 1e-5 of the weights and threshold (the kernel and the sum round
// by a few 1e-8 of those). So the skipping changes which samples are computed, never a result.
#pragma once
#include <glm/glm.hpp>

#include <vector>

#include "raster/march/metaball_field.h"
#include "raster/march/ray_packet.h"
#include "raster/simd/simd.h"

namespace tessera::march {

class MetaballPacket {
public:
    float value(glm::vec3 p) const { return field_.value(p); }
    glm::vec3 gradient(glm::vec3 p) const { return field_.gradient(p); }
    void values(const float* x, const float* y, const float* z, float* out) const { field_.values(x, y, z, out); }
    void gradients(const float* x, const float* y, const float* z, float* gx, float* gy, float* gz) const {
        field_.gradients(x, y, z, gx, gy, gz);
    }

    // The lanes whose ray might reach the surface (f >= 0) at some point with t in
    // [t_from, t_to]; a lane left out has f < 0 at every sample there, as values() computes it.
    simd::vmask may_reach(simd::vfloat t_from, simd::vfloat t_to) const;

    const MetaballField& field() const { return field_; }
    size_t size() const { return field_.size(); }

private:
    friend class MetaballField;  // cull() fills the packet

    template <class Kernel>
    simd::vfloat bound(const Kernel& kernel, simd::vfloat t_from, simd::vfloat t_to) const;

    struct alignas(64) Lanes {
        float v[kMarchLanes];
    };
    MetaballField field_;          // the balls the packet's rays cross
    std::vector<Lanes> closest_;   // per ball: t_c of each lane's ray
    std::vector<Lanes> miss2_;     // per ball: m^2 of each lane's ray
    std::vector<float> centre_norm_, positive_weight_;  // per ball: |c|, max(w, 0)
    Lanes origin_norm_{};          // |o| per lane
    float reach_ = 0.0f;           // the threshold less the rounding margin
};

}  // namespace tessera::march
