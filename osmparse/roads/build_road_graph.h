// Stage 6: the road graph. Highway ways (WGS84) -> straight node-to-node edges in local
// metres with a width, a class and which sides get a sidewalk.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "common/scene.h"
#include "osmparse/core/osm_data.h"
#include "osmparse/core/params.h"
#include "common/projection.h"
#include "osmparse/core/report.h"

namespace citygen {

// One straight piece of carriageway between two OSM nodes. As in the thesis the project started
// from (see README), every edge is a single straight segment: a way with many nodes yields many
// edges that meet at degree-2 joins; only nearly collinear runs are merged into one edge (the
// skipped nodes then lie within a few centimetres of the straight piece).
struct RoadGraphEdge {
    int64_t way_id = 0;
    int64_t from_node = 0, to_node = 0;
    Vec2 from, to;
    double width = 0;
    RoadClass road_class = RoadClass::Other;
    int lanes = 0;
    bool oneway = false;
    bool bridge = false;
    bool sidewalk_left = false, sidewalk_right = false;  // relative to from -> to
};

struct RoadGraph {
    std::vector<RoadGraphEdge> edges;  // sorted by (way id, position along the way)
};

// The scene's road class for a highway=* value (links map to their road).
RoadClass road_class_of(const std::string& highway);

// Why a highway way is not a carriageway, or nullopt when it is one.
std::optional<ReportReason> carriageway_exclusion(const OsmTags& tags, const RoadParams& params);

// Default carriageway width in metres per highway=* value, two-way or one-way: the one
// table (docs/roads.md shows it).
double default_road_width(const std::string& highway, bool oneway);

// oneway=yes|true|1|-1, or implied (motorway, junction=roundabout|circular) unless
// oneway=* says otherwise.
bool is_oneway(const OsmTags& tags);

// bridge=* but bridge=no: the way keeps its own deck on a height field (common/bridge_deck.h).
bool is_bridge(const OsmTags& tags);

// covered=* but covered=no: the way runs under an arcade, a building's passage or a roof. It is
// drawn at the ground where it is (dropping it would cut the network); with a height field it is
// counted (ReportReason::Covered), as what covers it is not fitted to the terrain.
bool is_covered(const OsmTags& tags);

// Width of a carriageway: `width` (any unit parse_osm_length knows), else `lanes` x
// params.lane_width, else default_road_width() for the way's class and is_oneway(). Unparseable or absurd values (width
// outside [1, params.max_width], lanes outside [1, 12]) fall back to the next rule and
// are noted in `report` under "road edges" when a report is given.
double road_width(const OsmTags& tags, const RoadParams& params, ParseReport* report);

// Sidewalks on the left and right of the way's direction: sidewalk=both|left|right|no|
// none|separate and sidewalk:left/right/both=yes|no|separate where tagged, else by class
// (roads where people live and shop yes; motorways, links, service, living streets no).
struct SidewalkSides {
    bool left = false, right = false;
};
SidewalkSides sidewalk_sides(const OsmTags& tags);

// Splits included highway ways at every node shared with another included way (and at
// every node), then merges consecutive pieces of the same way at
// degree-2 nodes where the direction changes by less than params.merge_angle_deg.
// `with_terrain` (osmparse --dem): the covered ways kept are counted, a note under "road ways".
RoadGraph build_road_graph(const OsmData& osm, const Projection& projection,
                           const RoadParams& params, ParseReport& report, bool with_terrain = false);

}  // namespace citygen
