// hash.h is header-only (constexpr, inlined into vector loops); this file checks at compile
// time that the mix is the one documented, so a change to it is a deliberate one.
#include "procedural/hash.h"

namespace tessera::procedural {
static_assert(mix32(0) == 0, "lowbias32 maps 0 to 0");
static_assert(hash(1, 2, 3, 4) != hash(1, 2, 3, 5), "coordinates must change the hash");
static_assert(unit_float(0xffffffffU) < 1.0f, "unit_float stays below 1");
}  // namespace tessera::procedural
