// Stage 8: road polygons. Road graph -> one quadrangle per edge and one joint polygon per
// junction (thesis ch. 3.2.3; the geometry itself is in road_layout.h).
#pragma once

#include <vector>

#include "common/scene.h"
#include "osmparse/core/report.h"
#include "osmparse/roads/build_road_graph.h"
#include "osmparse/roads/road_layout.h"

namespace citygen {

// How exactly quads and joints meet: the widest hole beyond a quad's end (metres) and
// the largest overlap of a quad with its joint (square metres).
constexpr double kJoinTolerance = 0.01;
constexpr double kJoinOverlapTolerance = 0.01;

struct RoadSurface {
    std::vector<RoadEdge> roads;
    std::vector<Joint> joints;
    RoadLayout layout;              // per graph edge and node; sidewalks follow its joins (its
                                    // quads and joint polygons are moved into `roads` and
                                    // `joints`, its ends' gap points freed; build_sidewalks
                                    // takes the rest)
    std::vector<int> road_of_edge;  // index into `roads` per graph edge, -1 when dropped
};

// Half widths of every edge's carriageway.
std::vector<SideWidths> carriageway_widths(const RoadGraph& graph);

// The scene's roads and joints from the graph's carriageway layout (narrow_roads makes it):
// quads CCW and convex, joints CCW and simple, each quad's end lying on its joint's
// boundary. Edges whose quad would fold are dropped and counted.
RoadSurface build_road_polygons(const RoadGraph& graph, RoadLayout layout, ParseReport& report);

}  // namespace citygen
