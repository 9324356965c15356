#include "build_road_polygons.h"

namespace citygen {

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
        out.joints.push_back(std::move(j));
    }
    report.kept("road joints", static_cast<int64_t>(out.joints.size()));
    return out;
}

}  // namespace citygen
