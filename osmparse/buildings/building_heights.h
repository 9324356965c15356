// Building heights from OSM's Simple 3D Buildings tags, with a seeded random fallback.
#pragma once

#include "common/scene.h"
#include "osmparse/core/osm_data.h"
#include "osmparse/core/params.h"
#include "osmparse/core/report.h"

namespace citygen {

struct BuildingHeight {
    double min_height = 0;  // metres above ground where this building or part starts
    double height = 0;      // metres above ground of its top (roof included, as OSM tags it)
    int levels = 0;         // storeys between min_height and height
    HeightSource source = HeightSource::Random;
};

// The height rules, in order:
//   top:    `height` (m, ft, ' and "), else `building:levels` x level_height, else a
//           random height in [random_min_height, random_max_height] drawn from
//           hash_keys(seed, OSM type, OSM id), so it does not depend on reading order;
//   bottom: `min_height`, else `building:min_level` x level_height, else 0.
// `roof:levels` is ignored. A tag that does not parse or is absurd (negative, above
// max_height, a bottom not below the top) is ignored as if absent and counted as a
// note under `kind` in the report.
BuildingHeight building_height(const OsmTags& tags, OsmRef ref, const BuildingParams& params,
                               ParseReport& report, ReportKind kind);

}  // namespace citygen
