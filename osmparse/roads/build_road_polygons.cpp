#include "build_road_polygons.h"

#include <algorithm>

#include "polygon_overlap.h"

namespace citygen {

namespace {

// The widest hole (metres) just beyond the end of `roads[r]` at joint `j`: ground
// covered by neither the joint nor another of its quads.
double hole_beyond_end(const std::vector<RoadEdge>& roads, const Joint& joint, uint32_t r, bool at_from) {
    const Ring& q = roads[r].quad;
    const Vec2 c1 = at_from ? q[0] : q[1], c2 = at_from ? q[3] : q[2];
    const Vec2 beyond = normalize((c1 + c2) * 0.5 - (q[0] + q[1] + q[2] + q[3]) * 0.25) * 0.01;
    double hole = 0;
    for (int k = 1; k < 10; ++k) {
        const Vec2 p = c1 + (c2 - c1) * (k / 10.0) + beyond;
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

RoadSurface build_road_polygons(const RoadGraph& graph, const RoadParams& params, ParseReport& report) {
    RoadSurface out;
    out.layout = layout_road_polygons(graph, carriageway_widths(graph), params.miter_limit);
    out.road_of_edge.assign(graph.edges.size(), -1);
    for (size_t e = 0; e < graph.edges.size(); ++e) {
        const RoadGraphEdge& g = graph.edges[e];
        if (out.layout.absorbed[e]) {
            report.dropped("road edges", "absorbed into a merged junction");
            continue;
        }
        if (out.layout.quads[e].empty()) {
            report.dropped("road edges", "too short for its junctions");
            continue;
        }
        RoadEdge r;
        r.osm = {OsmType::Way, g.way_id};
        r.from_node = g.from_node;
        r.to_node = g.to_node;
        r.centreline = {g.from, g.to};
        r.quad = out.layout.quads[e];
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
    report.kept("road edges", static_cast<int64_t>(out.roads.size()));

    for (const NodeLayout& node : out.layout.nodes) {
        if (node.kind != JoinKind::Joint) continue;
        report.read("road joints");
        if (node.joint.empty()) {
            report.dropped("road joints", "nothing left of the polygon");
            continue;
        }
        if (!node.members.empty()) report.note("road joints", "merged from nearby junctions");
        if (node.joint_is_hull) report.note("road joints", "star or hull polygon stands in for a tangled one");
        Joint j;
        j.osm = {OsmType::Node, node.node};
        j.polygon = node.joint;
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
                report.note("road joints", "a quad end leaves a hole over 1 cm");
            if (clipped_area(j.polygon, out.roads[road].quad) > kJoinOverlapTolerance)
                report.note("road joints", "a quad overlaps its joint by over 0.01 m2");
        }
        out.joints.push_back(std::move(j));
    }
    report.kept("road joints", static_cast<int64_t>(out.joints.size()));
    return out;
}

}  // namespace citygen
