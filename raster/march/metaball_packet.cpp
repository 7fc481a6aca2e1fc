#include "raster/march/metaball_packet.h"

namespace tessera::march {

template <class Kernel>
simd::vfloat MetaballPacket::bound(const Kernel& kernel, simd::vfloat t_from, simd::vfloat t_to) const {
    using simd::vfloat;
    // |t| of the stretch's farther end, for the rounding slack of o + t d.
    const vfloat extent = simd::max(t_to, t_from * vfloat(-1.0f));
    const vfloat origin = vfloat::load(origin_norm_.v) + extent;
    vfloat sum(0.0f);
    for (size_t b = 0; b < closest_.size(); ++b) {
        const vfloat closest = vfloat::load(closest_[b].v);
        const vfloat along = simd::min(simd::max(closest, t_from), t_to) - closest;
        const vfloat distance = simd::sqrt(vfloat::load(miss2_[b].v) + along * along);
        const vfloat slack = vfloat(1e-5f) * (origin + vfloat(centre_norm_[b]));
        const vfloat gap = simd::max(distance - slack, vfloat(0.0f));
        sum = sum + vfloat(positive_weight_[b]) * kernel.at(gap * gap * vfloat(field_.inv_r2_[b])).value;
    }
    return sum;
}

simd::vmask MetaballPacket::may_reach(simd::vfloat t_from, simd::vfloat t_to) const {
    simd::vfloat sum;
    switch (field_.style_.kernel) {
    case MetaballKernel::wyvill: sum = bound(WyvillKernel{}, t_from, t_to); break;
    case MetaballKernel::perlin: sum = bound(PerlinKernel{}, t_from, t_to); break;
    default: sum = bound(field_.blinn_, t_from, t_to); break;
    }
    // Not "sum < reach": a NaN anywhere keeps the lane.
    return simd::andnot(sum < simd::vfloat(reach_), simd::vmask(true));
}

}  // namespace tessera::march
