// Stage 12 (optional, --fill-empty-blocks): buildings in the blocks of the road graph that the map
// left empty (Bruneton's Rama: buildings generated in road-graph zones).
#pragma once

#include <vector>

#include "common/scene.h"
#include "osmparse/core/params.h"
#include "osmparse/core/report.h"
#include "osmparse/roofs/build_roofs.h"

namespace citygen {

// The blocks are the bounded faces of the road graph (dead ends pruned). A block is filled when
// no mapped building lies in it, it is built-up (at least min_buildings_near mapped buildings
// within near_distance of it: a stand-in for built-up land use, which the scene does not carry
// yet) and, shrunk by the widest road's half width, the sidewalk and the setback, its area is in
// [min_block_area, max_block_area]. The shrunk block is split recursively across the long axis of
// its minimum-area rectangle until lots are at most max_lot_area; lots without a side on the
// street are dropped; each lot gets one building, the lot shrunk by the setback, with the height
// of the type-and-area rule for `yes` (seeded jitter), default roof, colours and materials.
// Footprints that would overlap a road, joint, sidewalk or mapped building are dropped.
// Generated buildings have `generated` set and OSM identity w-1, w-2, ... (none in the map).
// Their roofs follow `roof_evidence`, what the map's tagged roofs say of the region (build_roofs.h).
// Counts go to "generated buildings" in the report.
std::vector<Building> fill_empty_blocks(const Scene& scene, const BuildingParams& buildings,
                                        const BlockParams& params, double sidewalk_width,
                                        const RoofEvidence& roof_evidence, ParseReport& report);

}  // namespace citygen
