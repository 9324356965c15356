// Stage 2: buildings. OSM building areas (WGS84) -> clean footprints in local metres
// with heights.
#pragma once

#include <vector>

#include "common/scene.h"
#include "osmparse/core/osm_data.h"
#include "osmparse/core/params.h"
#include "common/projection.h"
#include "osmparse/core/report.h"

namespace citygen {

// One Building per outer ring (with its holes) of every `building=*` or `building:part=*`
// area whose type is not in params.ignore_types. Footprints are cleaned by
// clean_footprint(), heights come from building_height(). A building outline that
// contains building:part outlines is dropped in favour of its parts (Simple 3D
// Buildings). The result is sorted by OSM identity, so it does not depend on the order
// libosmium assembled the areas in. Counts go to `report` under "buildings",
// "building parts" and "building holes".
std::vector<Building> build_buildings(const OsmData& osm, const Projection& projection,
                                      const BuildingParams& params, ParseReport& report);

}  // namespace citygen
