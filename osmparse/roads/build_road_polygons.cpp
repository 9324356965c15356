#include "osmparse/roads/build_road_polygons.h"

#include <algorithm>

#include "osmparse/polygons/polygon_overlap.h"
#include "osmparse/roads/road_geometry.h"

namespace citygen {

namespace {

// The widest hole (metres) just beyond the end of `roads[r]` at joint `j`: ground
// covered by neither the joint nor another of its quads.
double hole_beyond_end(const std::vector<RoadEdge>& roads, const Joint& joint, uint32_t r, bool at_from) {
    double hole = 0;
    for (Vec2 p : points_beyond_quad_end(roads[r].quad, at_from)) {
        if (point_in_ring(p, joint.polygon)) continue;
        double nearest = distance_to_boundary(p, joint.polygon);
        for (uint32_t other : joint.edges) {
            if (other == r) continue;
            if (point_in_ring(p, roads[other].quad)) {
                nearest = 0;
                break;
            }
            nearest = std::min(nearest, distance_to_boundary(p, roads[other].quad));
        }
        hole = std::max(hole, nearest);
    }
    return hole;
}

}  // namespace

std::vector<SideWidths> carriageway_widths(const RoadGraph& graph) {
    std::vector<SideWidths> w;
    w.reserve(graph.edges.size());
    for (const RoadGraphEdge& e : graph.edges) w.push_back({0.5 * e.width, 0.5 * e.width});
    return w;
}

RoadSurface build_road_polygons(const RoadGraph& graph, RoadLayout layout, ParseReport& report) {
    RoadSurface out;
    out.layout = std::move(layout);
    out.road_of_edge.assign(graph.edges.size(), -1);
    // Exactly (the roads and joints are the scene's, kept to the end of the parse).
    out.roads.reserve(quad_count(out.layout));
    out.joints.reserve(joint_count(out.layout));
    for (size_t e = 0; e < graph.edges.size(); ++e) {
        const RoadGraphEdge& g = graph.edges[e];
        if (out.layout.absorbed[e]) {
            report.dropped(ReportKind::RoadEdges, ReportReason::AbsorbedIntoMergedJunction);
            continue;
        }
        if (out.layout.quads[e].empty()) {
            report.dropped(ReportKind::RoadEdges, ReportReason::TooShortForJunctions);
            continue;
        }
        RoadEdge r;
        r.osm = {OsmType::Way, g.way_id};
        r.from_node = g.from_node;
        r.to_node = g.to_node;
        r.centreline = {g.from, g.to};
        r.quad = std::move(out.layout.quads[e]);  // nothing reads the layout's quads after this
        r.width = g.width;
        r.road_class = g.road_class;
        r.lanes = g.lanes;
        r.oneway = g.oneway;
        r.bridge = g.bridge;
        r.sidewalk_left = g.sidewalk_left;
        r.sidewalk_right = g.sidewalk_right;
        out.road_of_edge[e] = static_cast<int>(out.roads.size());
        out.roads.push_back(std::move(r));
    }
    report.kept(ReportKind::RoadEdges, static_cast<int64_t>(out.roads.size()));

    for (NodeLayout& node : out.layout.nodes) {
        // Nothing reads an end's gap points after the joint is shaped (the sidewalks' outline
        // shapes its own): freed, as the joint polygon is moved into the scene's joint.
        for (NodeLayout::End& end : node.ends) std::vector<Vec2>().swap(end.gap_points);
        if (node.kind != JoinKind::Joint) continue;
        report.read(ReportKind::RoadJoints);
        if (node.joint.empty()) {
            report.dropped(ReportKind::RoadJoints, ReportReason::NothingLeftOfJoint);
            continue;
        }
        if (!node.members.empty()) report.note(ReportKind::RoadJoints, ReportReason::MergedFromNearbyJunctions);
        if (node.joint_is_hull) report.note(ReportKind::RoadJoints, ReportReason::StarOrHullJoint);
        Joint j;
        j.osm = {OsmType::Node, node.node};
        j.polygon = std::move(node.joint);
        const int index = static_cast<int>(out.joints.size());
        for (const NodeLayout::End& end : node.ends) {
            const int road = out.road_of_edge[end.edge];
            if (road < 0) continue;
            j.edges.push_back(static_cast<uint32_t>(road));
            (end.at_from ? out.roads[road].from_joint : out.roads[road].to_joint) = index;
        }
        // Quads meet their joint edge to edge; what the layout could not achieve in a
        // tangle of short edges is counted.
        for (const NodeLayout::End& end : node.ends) {
            const int road = out.road_of_edge[end.edge];
            if (road < 0) continue;
            if (hole_beyond_end(out.roads, j, static_cast<uint32_t>(road), end.at_from) > kJoinTolerance)
                report.note(ReportKind::RoadJoints, ReportReason::HoleBeyondQuadEnd);
            if (clipped_area(j.polygon, out.roads[road].quad) > kJoinOverlapTolerance)
                report.note(ReportKind::RoadJoints, ReportReason::QuadOverlapsJoint);
        }
        out.joints.push_back(std::move(j));
    }
    report.kept(ReportKind::RoadJoints, static_cast<int64_t>(out.joints.size()));
    return out;
}

}  // namespace citygen
