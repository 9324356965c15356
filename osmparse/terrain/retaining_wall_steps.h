// The ground steps at a retaining wall (issue 22): after the roads are laid into the field
// (fit_terrain.h), the nodes on each wall's low side (the right of its line, OSM's convention)
// within a cell's diagonal of it are lowered so the ground at its foot is the high side's
// ground less the wall's height, and a shoulder beyond blends that back into the field, as a
// road's does. docs/terrain.md, "Retaining walls".
#pragma once

#include <cstdint>
#include <vector>

#include "common/scene.h"
#include "osmparse/core/report.h"

namespace citygen {

// Lowers the field on the walls' low sides and counts it. The high side's ground is the field at
// the nearest point of the wall's line as it was before any wall was cut in; a node is only ever
// lowered (where the field already falls further, as a DEM that resolves the wall does, it is
// left as it is), to the lowest any wall asks. Nodes flagged in `under_ways` (the roads' and
// paths' corridors, fit_terrain.h's way_corridor_nodes) are left: a road is never dug under.
void step_terrain_at_walls(HeightField& field, const std::vector<RetainingWall>& walls,
                           const std::vector<uint8_t>& under_ways, ParseReport& report);

}  // namespace citygen
