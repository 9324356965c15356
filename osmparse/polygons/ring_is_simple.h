// Is a footprint ring simple? Only osmparse asks (footprints, sidewalks, joints, blocks), so the
// CGAL sweep behind it lives here rather than in common/.
#pragma once

#include "common/geometry.h"

namespace citygen {

// True when the ring has >= 3 distinct points, no two non-adjacent edges touch and no two
// adjacent edges fold back over each other. O(n log n), exact for any double coordinates.
bool ring_is_simple(const Ring& ring);
// The sweep ring_is_simple uses for all but small rings (exposed for tests).
bool ring_is_simple_sweep(const Ring& ring);

}  // namespace citygen
