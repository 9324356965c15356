// Stage 9 (lanes, in the road section) and stage 16 (crossings): lanes and road markings
//: a lane layout per road from the tags osm2lanes reads
// (lanes, lanes:forward|backward, turn:lanes*, cycleway*, busway*, parking:*), and where
// markings go: centre line, lane dividers and edge lines per road, zebra crossings and
// stop lines per node. A few numbers each; render paints them at shading time.
#pragma once

#include <vector>

#include "common/scene.h"
#include "osmparse/core/osm_data.h"
#include "common/projection.h"
#include "osmparse/core/report.h"

namespace citygen {

struct LaneLayout {
    int forward = 1, backward = 1;  // motor-traffic lanes along and against the way
    CentreLine centre = CentreLine::None;
    bool edge_lines = false;
    bool cycle_left = false, cycle_right = false;  // cycleway=lane|cycleway:both=lane: both; :left/:right
};

// Lanes: lanes:forward / lanes:backward when tagged; else `lanes` (or the count of
// turn:lanes entries) split between the directions (oneway: all forward; oneway=-1: all
// backward; two-way: the odd lane forward); else by class (one per direction, one for
// oneway, service and living streets). Centre line: none on oneway roads, single-lane
// roads and carriageways narrower than 5 m; double on two-way roads of 4+ lanes; solid on
// primary, secondary and trunk; dashed elsewhere. Edge lines on motorway to secondary.
// Unusable lane tags (lanes=banana) fall back and are noted under "road lanes".
LaneLayout lane_layout(const OsmTags& tags, RoadClass road_class, double width, ParseReport* report);

// Carriageway width the cycle, bus and parking lanes add when `width` is not tagged:
// cycleway*=lane 1.5 m per side, busway*=lane 3 m per side, parking:*=lane|parallel|
// diagonal|perpendicular (or parking:lane:*) 2 m per side.
double lane_extras_width(const OsmTags& tags);

// Fills lanes_forward/backward, centre_line and edge_lines of every road from its way's tags.
void lay_out_lanes(std::vector<RoadEdge>& roads, const OsmData& osm, ParseReport& report);

// Zebra crossings at highway=crossing nodes marked as such (crossing=zebra|marked|
// uncontrolled, crossing:markings other than no) and stop lines at highway=traffic_signals
// nodes, each on the road whose carriageway holds the node (nearest centreline within half
// its width + 1 m). A stop line covers the lanes travelling towards the nearer end of the
// road (right-hand traffic). Nodes on junction polygons or off every road are counted.
std::vector<Crossing> place_crossings(const OsmData& osm, const Projection& projection, const Scene& scene,
                                      ParseReport& report);

}  // namespace citygen
