// A marchable surface = a field plus how it bounds a packet of rays. bind() fills each lane's
// [t0, t1] and returns the field to march for that packet (possibly a culled copy kept in the
// caller's scratch, so nothing is shared between threads); validate() throws
// std::invalid_argument for bounds that cannot hold a surface:
// - SlabSurface: a field that lies between two horizontal planes (the terrain and its
//   3-D noise);
// - MetaballSurface: metaballs, culled per tile to the balls its rays may meet (bind_tile: a
//   tile far from every ball marches nothing) and per packet to the balls the packet's rays
//   cross, which also bound the field along each ray (metaball_packet.h).
#pragma once
#include "raster/march/bounds.h"
#include "raster/march/march_field.h"
#include "raster/march/march.h"
#include "raster/march/metaball_field.h"
#include "raster/march/metaball_packet.h"
#include "raster/march/ray_generation.h"
#include "raster/core/tile.h"

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

    struct Scratch {
        MetaballField tile;                    // the balls a tile's rays may meet
        const MetaballField* from = nullptr;   // what packets are culled from: the tile's, or all
        MetaballPacket packet;
    };

    void validate() const {}  // the field validated its balls when it was built

    // Culls to the balls the rays of the tile's pixels (x0..x1-1, y0..y1-1) may meet, from
    // the cone of its corner pixels' rays; false when none remains (nothing to march).
    bool bind_tile(const RayGenerator& rays, const TileRect& rect, Scratch& scratch) const {
        const glm::vec3 corners[] = {rays.direction(rect.x0, rect.y0), rays.direction(rect.x1 - 1, rect.y0),
                                     rays.direction(rect.x0, rect.y1 - 1), rays.direction(rect.x1 - 1, rect.y1 - 1)};
        field.cull(rays.eye(), corners, scratch.tile);
        scratch.from = &scratch.tile;
        return scratch.tile.size() > 0;
    }

    const MetaballPacket& bind(const RayPacket& rays, float t_far, PacketSegments& segments,
                               Scratch& scratch) const {
        (scratch.from ? *scratch.from : field).cull(rays, t_far, scratch.packet, segments);
        return scratch.packet;
    }
};

}  // namespace tessera::march
