// Normal maps from height maps (Blinn's bump mapping): a tangent-space normal per texel from
// central differences of the heights, n = normalize(-s dh/du, -s dh/dv, 1), stored as RGB with
// (0, 0, 1) -> (128, 128, 255), the flat blue of every normal map.
//
// Convention: u runs along +x (columns), v runs up the image (OpenGL / "Y+" normal maps, the
// green channel points up), so dh/dv = -dh/drow. Parallel over rows; deterministic.
#pragma once
#include <cstdint>
#include <vector>

#include "procedural/grid.h"

namespace tessera::procedural {

struct NormalMap {
    int width = 0;
    int height = 0;
    std::vector<float> xyz;  // 3 floats per texel, unit length, z > 0
};

// `strength` scales height differences (heights per texel) before normalising: a map with
// heights in [0, 1] spanning many texels per feature needs strength >> 1 to show relief.
// Edges wrap (periodic, for tileable maps) or repeat the edge texel (clamped).
NormalMap normal_map(const Grid& heights, float strength, Boundary boundary);

// RGB8, (n * 0.5 + 0.5) * 255 rounded: (0, 0, 1) encodes as (128, 128, 255).
std::vector<uint8_t> encode_normals_rgb8(const NormalMap& normals);

}  // namespace tessera::procedural
