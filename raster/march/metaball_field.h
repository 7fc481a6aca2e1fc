// Metaballs (Blinn 1982): f(p) = sum_i w_i K(|p - c_i|^2 / R_i^2) - T, positive inside
// the blob, with the analytic gradient sum_i w_i dK/ds 2 (p - c_i) / R_i^2 (analytically, not
// by differences).
//
// Every kernel here has finite support R_i (metaball_kernel.h), so a ball contributes nothing
// to a ray that misses its support sphere. cull() uses that: for a packet of rays it keeps
// only the balls some ray of the packet crosses and gives each ray the hull of the support
// intervals it crosses as its march bounds. Along those rays the culled field equals the full
// one exactly, and a far ball, or empty sky, costs one ray-sphere test per packet. The culled
// balls also bound the field along each ray (metaball_packet.h), so the march skips the
// stretches where no sum of kernels can reach the threshold.
#pragma once
#include <glm/glm.hpp>

#include <span>
#include <vector>

#include "raster/march/march.h"
#include "raster/march/metaball_kernel.h"
#include "raster/march/ray_packet.h"

namespace tessera::march {

struct Metaball {
    glm::vec3 centre{0.0f};
    float radius = 1.0f;  // support radius R
    float weight = 1.0f;
};

struct MetaballStyle {
    MetaballKernel kernel = MetaballKernel::wyvill;
    float threshold = 0.5f;             // T, the level set
    float blinn_sharpness = 6.907755f;  // a = ln 1000 (see metaball_kernel.h)
};

class MetaballPacket;

class MetaballField {
public:
    MetaballField() : blinn_(MetaballStyle{}.blinn_sharpness) {}
    // Throws std::invalid_argument for a non-finite centre or weight, a radius that is not
    // positive and finite, a threshold that is not positive and finite, or a non-positive
    // Blinn sharpness.
    MetaballField(const std::vector<Metaball>& balls, const MetaballStyle& style);

    float value(glm::vec3 p) const;
    glm::vec3 gradient(glm::vec3 p) const;
    void values(const float* x, const float* y, const float* z, float* out) const;
    // gradient() at kMarchLanes points, bit for bit (the same operations in the same order).
    void gradients(const float* x, const float* y, const float* z, float* gx, float* gy, float* gz) const;

    // Fills `subset` (whose storage is reused) with the balls whose support may meet a ray from
    // `eye` with a direction in the cone spanned by `corners` (a tile's corner pixels: every
    // pixel ray of the tile lies in it), in their order; a cone wider than 1.5 rad keeps all.
    void cull(glm::vec3 eye, std::span<const glm::vec3> corners, MetaballField& subset) const;

    // Fills `packet` (whose storage is reused) with the balls whose support some live lane of
    // `rays` crosses within [0, t_far] and each lane's closest approach to them, and
    // `segments` with each lane's march bounds: the hull of the support intervals it crosses,
    // bit for bit what bounds() gives that lane (the ray-sphere tests run in lanes).
    void cull(const RayPacket& rays, float t_far, MetaballPacket& packet,
              PacketSegments& segments) const;

    // The bounds of one ray (the scalar counterpart of cull, over all balls).
    Interval bounds(glm::vec3 o, glm::vec3 d, float t_far) const;

    size_t size() const { return cx_.size(); }
    Metaball ball(size_t i) const { return {{cx_[i], cy_[i], cz_[i]}, radius_[i], weight_[i]}; }

private:
    friend class MetaballPacket;

    template <class Kernel>
    void accumulate(const Kernel& kernel, const float* x, const float* y, const float* z,
                    float* sum) const;
    template <class Kernel>
    void accumulate_gradient(const Kernel& kernel, const float* x, const float* y, const float* z, float* gx,
                             float* gy, float* gz) const;
    // The culled subsets: start empty with this field's style, take ball b of this field.
    void begin_subset(MetaballField& subset) const;
    void copy_ball(size_t b, MetaballField& subset) const;

    MetaballStyle style_;
    BlinnKernel blinn_;
    // Structure of arrays so values() streams through the balls with lanes innermost.
    std::vector<float> cx_, cy_, cz_, radius_, inv_r2_, weight_;
};

}  // namespace tessera::march
