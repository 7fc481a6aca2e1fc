// Welding: vertices whose every attribute (position, normal, uv, tangent: whichever streams the
// mesh has) is bit-for-bit identical become one vertex. Importers that hand out one vertex per
// face corner (Assimp's OBJ, PLY and STL readers) produce three times the vertices an indexed
// mesh needs, which the vertex stage would transform three times over.
//
// Exact bits, not a distance: nothing that differs (a uv seam, a hard edge's two normals, -0
// and +0) is merged, so the shaded picture cannot change. The first occurrence of each vertex
// keeps its place, so the result does not depend on anything but the input, and an already
// indexed mesh comes out unchanged.
#pragma once
#include "raster/core/mesh.h"

namespace tessera::io {

// Returns how many vertices were merged away.
size_t weld_vertices(Mesh& mesh);

}  // namespace tessera::io
