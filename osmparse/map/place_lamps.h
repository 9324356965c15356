// Stage 13: street lamps. Every highway=street_lamp node, plus lamps generated along the
// roads (OSM maps far fewer lamps than streets have): one per params.spacing metres on
// average, alternating sides, just beyond the carriageway's edge (on the sidewalk where
// there is one), never inside a road, joint or building, and never closer than
// params.min_distance_to_tagged to a mapped lamp.
#pragma once

#include <vector>

#include "common/scene.h"
#include "osmparse/core/osm_data.h"
#include "osmparse/core/params.h"
#include "common/projection.h"
#include "osmparse/core/report.h"

namespace citygen {

// Generated lamps carry the OSM way of the road they stand beside. Tagged lamps that
// fall on our (wider than mapped) road surface are moved just off it; those inside a
// building are dropped. Uses scene.roads, joints, sidewalks and buildings.
std::vector<Lamp> place_lamps(const OsmData& osm, const Projection& projection, const Scene& scene,
                              const LampParams& params, uint64_t seed, ParseReport& report);

}  // namespace citygen
