#include "narrow_roads.h"

#include <algorithm>
#include <set>

#include "polygon_overlap.h"
#include "road_layout.h"

namespace citygen {

namespace {

constexpr double kNarrowStep = 0.85;     // width kept per step
constexpr double kNarrowestRoad = 0.5;   // metres: even with --road-min-width 0, narrower is gone
constexpr int kLayoutRounds = 6;

bool overlaps(const BuildingIndex& index, const Ring& piece) {
    double largest = 0;
    index.overlap(piece, &largest);
    return largest > kRoadBuildingOverlapTolerance;
}

}  // namespace

RoadGraph narrow_roads(RoadGraph graph, const std::vector<Building>& buildings,
                       const RoadParams& params, ParseReport& report) {
    const BuildingIndex index(buildings);
    std::vector<bool> keep(graph.edges.size(), true), narrowed(graph.edges.size(), false);
    auto narrow = [&](size_t e) {
        graph.edges[e].width *= kNarrowStep;
        narrowed[e] = true;
        if (graph.edges[e].width < std::max(params.min_width, kNarrowestRoad)) keep[e] = false;
    };

    // 1. The edge's whole rectangle, as in the thesis.
    for (size_t e = 0; e < graph.edges.size(); ++e) {
        const RoadGraphEdge& edge = graph.edges[e];
        while (keep[e]) {
            const double h = 0.5 * edge.width;
            if (!overlaps(index, quad_for_cuts(edge, {h, h}, {}, {}))) break;
            narrow(e);
        }
    }
    auto compact = [&] {
        RoadGraph kept;
        std::vector<bool> kept_narrowed;
        for (size_t e = 0; e < graph.edges.size(); ++e) {
            if (keep[e]) {
                kept.edges.push_back(graph.edges[e]);
                kept_narrowed.push_back(narrowed[e]);
            } else {
                report.dropped("road edges", "narrower than road-min-width beside a building");
            }
        }
        graph = std::move(kept);
        narrowed = std::move(kept_narrowed);
        keep.assign(graph.edges.size(), true);
    };
    compact();

    // 2. Miters and joints reach beyond the rectangles: check the laid-out pieces. After
    // the first round only pieces at nodes whose edges were narrowed can have changed.
    std::set<int64_t> dirty;
    for (int round = 0; round < kLayoutRounds; ++round) {
        auto needs_check = [&](int64_t node) { return round == 0 || dirty.count(node) > 0; };
        std::vector<SideWidths> widths;
        for (const RoadGraphEdge& e : graph.edges) widths.push_back({0.5 * e.width, 0.5 * e.width});
        const RoadLayout layout =
            round == 0 ? layout_road_polygons(graph, widths, params.miter_limit)
                       : layout_road_polygons(graph, widths, params.miter_limit, nullptr,
                                              [&](int64_t node) { return dirty.count(node) > 0; });
        std::set<size_t> offending;
        for (size_t e = 0; e < graph.edges.size(); ++e) {
            // A quad with no negative cut lies inside its rectangle, cleared above.
            const EdgeEndCut &a = layout.from_cut[e], &b = layout.to_cut[e];
            const bool within_rectangle = std::min({a.t_left, a.t_right, b.t_left, b.t_right}) >= 0;
            if (!layout.quads[e].empty() && !within_rectangle &&
                (needs_check(graph.edges[e].from_node) || needs_check(graph.edges[e].to_node)) &&
                overlaps(index, layout.quads[e]))
                offending.insert(e);
        }
        for (const NodeLayout& node : layout.nodes) {
            bool check = needs_check(node.node);
            for (int64_t m : node.members) check = check || needs_check(m);
            if (check && !node.joint.empty() && overlaps(index, node.joint))
                for (const NodeLayout::End& end : node.ends) offending.insert(end.edge);
        }
        if (offending.empty()) break;
        dirty.clear();
        for (size_t e : offending) {
            narrow(e);
            dirty.insert(graph.edges[e].from_node);
            dirty.insert(graph.edges[e].to_node);
        }
        // A narrowed edge also changes the merged junction its node belongs to.
        for (const NodeLayout& node : layout.nodes) {
            bool touched = dirty.count(node.node) > 0;
            for (int64_t m : node.members) touched = touched || dirty.count(m) > 0;
            if (!touched) continue;
            dirty.insert(node.node);
            dirty.insert(node.members.begin(), node.members.end());
        }
        compact();
    }
    int64_t count = 0;
    for (bool n : narrowed) count += n;
    if (count) report.note("road edges", "narrowed beside a building", count);
    return graph;
}

}  // namespace citygen
