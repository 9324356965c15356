// Stage 7: roads against buildings. OSM centrelines and guessed widths often put a road
// surface into a building; as in the thesis the project started from (see README), such a road is
// narrowed step by step, and dropped once it would be narrower than params.min_width.
#pragma once

#include <vector>

#include "common/scene.h"
#include "osmparse/core/params.h"
#include "osmparse/core/report.h"
#include "osmparse/roads/build_road_graph.h"
#include "osmparse/roads/road_layout.h"

namespace citygen {

// Largest overlap (square metres) a road piece may have with one building.
constexpr double kRoadBuildingOverlapTolerance = 0.01;

// The narrowed graph and its carriageway layout (RoadLayout::quads etc. per edge of `graph`).
struct NarrowedRoads {
    RoadGraph graph;
    RoadLayout layout;
};

// First each edge's full rectangle, then the laid-out quads and joints are checked
// against the footprints; an overlapping edge (or every edge of an overlapping joint)
// loses 15% of its width per step. The layout is made once and, after each step, laid
// out again only where the narrowed edges change it. Counted under ReportKind::RoadEdges.
NarrowedRoads narrow_roads(RoadGraph graph, const std::vector<Building>& buildings,
                           const RoadParams& params, ParseReport& report);

}  // namespace citygen
