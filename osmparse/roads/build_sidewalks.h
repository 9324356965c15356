// Stage 10: sidewalks. An outer outline around every carriageway, laid out with the same
// joins (road_layout.h); the band between outline and carriageway is the sidewalk, in
// strips along edges and corner pieces around joints, raised by a curb.
#pragma once

#include <vector>

#include "common/scene.h"
#include "osmparse/core/params.h"
#include "osmparse/core/report.h"
#include "osmparse/roads/build_road_graph.h"
#include "osmparse/roads/build_road_polygons.h"

namespace citygen {

// Sides follow RoadGraphEdge::sidewalk_left/right (sidewalk=* tags or the class). A side
// whose sidewalk would reach into a building is narrowed in 25 cm steps and left out
// below 75 cm; pieces that still overlap a building, or overlap another road by more
// than half a square metre (the median of a dual carriageway), are dropped and counted.
// surface.layout is taken (the outline is shaped on its nodes, then freed): nothing reads
// it after the sidewalks.
std::vector<Sidewalk> build_sidewalks(const RoadGraph& graph, RoadSurface& surface,
                                      const std::vector<Building>& buildings,
                                      const SidewalkParams& params, double miter_limit,
                                      ParseReport& report);

}  // namespace citygen
