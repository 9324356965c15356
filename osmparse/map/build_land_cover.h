// Stage 14: land cover (with the sea, assemble_sea.h). OSM areas (closed ways and
// multipolygons, assembled by libosmium as buildings are) -> cleaned polygons with holes and
// one class each.
#pragma once

#include <optional>
#include <vector>

#include "common/scene.h"
#include "osmparse/core/osm_data.h"
#include "osmparse/core/params.h"
#include "common/projection.h"
#include "osmparse/core/report.h"

namespace citygen {

// Projects and cleans every land cover area (the footprint clean-up: repeated and collinear
// points, self-intersections, orientation, holes; slivers below params.min_area dropped),
// sorted by (class, OSM identity). Counted under ReportKind::LandCoverAreas, the kept ones also
// under their class's land_cover_row.
// Piers and breakwaters (is_pier) are kept only with_piers (on a height field, where
// fit_terrain.h raises the ground under them above the sea; on the flat ground the scene is
// what it was before they were read).
// A pier mapped as a line (osm.pier_lines) is a paved strip along it, `width` wide where tagged
// (1 to 50 m), else kLinearPierWidth: a rectangle per segment, reaching half its width past
// each end so bends leave no gap.
std::vector<LandCover> build_land_cover(const OsmData& osm, const Projection& projection,
                                        const BuildingParams& params, bool with_piers, ParseReport& report);

// The width of a pier mapped as a line without a usable width tag (metres): the median width of
// Monaco's 27 pier areas is 2.7 m (1.5 to 9.1 m), and a landing stage or jetty mapped as a line
// is one of the narrow ones.
constexpr double kLinearPierWidth = 3;

// The report row that counts the kept land cover of a class ("land cover: water", ...).
ReportKind land_cover_row(LandCoverClass c);

// Drops (and counts) polygons beyond the land cover limits of scene_limits.h, which the
// scene loader would refuse: a ring with too many points or wider than a region.
std::vector<LandCover> drop_land_cover_beyond_limits(std::vector<LandCover> cover, ParseReport& report);

}  // namespace citygen
