// A marchable surface = a field plus how it bounds a packet of rays. bind() fills each lane's
// [t0, t1] and returns the field to march for that packet (possibly a culled copy kept in the
// caller's scratch, so nothing is shared between threads); validate() throws
// std::invalid_argument for bounds that cannot hold a surface:
// - SlabSurface: a field that lies between two horizontal planes (the terrain and its
//   3-D noise);
// - MetaballSurface: metaballs, culled per packet to the balls the packet's rays cross, which
//   also bound the field along each ray (metaball_packet.h).
#pragma once
#include "raster/march/bounds.h"
#include "raster/march/march_field.h"
#include "raster/march/march.h"
#include "raster/march/metaball_field.h"
#include "raster/march/metaball_packet.h"

namespace tessera::march {

template <MarchField F>
struct SlabSurface {
    const F& field;
    Slab slab;

    struct Scratch {};

    void validate() const { slab.validate(); }

    const F& bind(const RayPacket& rays, float t_far, PacketSegments& segments, Scratch&) const {
        for (int i = 0; i < kMarchLanes; ++i) {
            const Interval s = slab.clip(rays.origin(i), rays.direction(i), t_far);
            segments.t0[i] = s.t0;
            segments.t1[i] = s.t1;
        }
        return field;
    }
};

struct MetaballSurface {
    const MetaballField& field;

    using Scratch = MetaballPacket;

    void validate() const {}  // the field validated its balls when it was built

    const MetaballPacket& bind(const RayPacket& rays, float t_far, PacketSegments& segments,
                               Scratch& packet) const {
        field.cull(rays, t_far, packet, segments);
        return packet;
    }
};

}  // namespace tessera::march
