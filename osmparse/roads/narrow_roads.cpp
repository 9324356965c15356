#include "osmparse/roads/narrow_roads.h"

#include <algorithm>
#include <set>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "osmparse/polygons/polygon_overlap.h"
#include "osmparse/roads/build_road_polygons.h"
#include "osmparse/roads/layout_state.h"

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

// The junctions the nodes `nodes` belong to, each once.
std::vector<const NodeLayout*> junctions_of(LayoutState& layout, const std::set<int64_t>& nodes) {
    std::set<int64_t> keys;
    std::vector<const NodeLayout*> out;
    for (int64_t v : nodes)
        if (const NodeLayout* j = layout.junction_of(v); j && keys.insert(j->node).second) out.push_back(j);
    return out;
}

// Step 2: the edges whose laid-out quad or joint overlaps a building, among the pieces at the
// nodes `dirty` holds (a quad by either end node, a joint by its key or a member), or all of
// them when `dirty` is null. The dirty nodes' junctions are looked up, not found by a walk over
// every junction: after the first round they are few.
std::set<uint32_t> offending_edges(LayoutState& layout, const BuildingIndex& index, const std::set<int64_t>* dirty) {
    const RoadGraph& graph = layout.graph;
    auto needs_check = [&](int64_t node) { return !dirty || dirty->count(node) > 0; };
    // The pieces are checked in parallel (the overlap tests are most of the stage's time).
    std::vector<char> quad_offends(graph.edges.size(), 0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, graph.edges.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t e = r.begin(); e != r.end(); ++e) {
            // A quad with no negative cut lies inside its rectangle, cleared in step 1.
            const EdgeEndCut &a = layout.out.from_cut[e], &b = layout.out.to_cut[e];
            const bool within_rectangle = std::min({a.t_left, a.t_right, b.t_left, b.t_right}) >= 0;
            quad_offends[e] = !layout.out.quads[e].empty() && !within_rectangle &&
                              (needs_check(graph.edges[e].from_node) || needs_check(graph.edges[e].to_node)) &&
                              overlaps(index, layout.out.quads[e]);
        }
    });
    std::vector<const NodeLayout*> junctions;
    if (dirty) junctions = junctions_of(layout, *dirty);
    else layout.for_each_junction([&](const NodeLayout& node) { junctions.push_back(&node); });
    std::vector<char> joint_offends(junctions.size(), 0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, junctions.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t k = r.begin(); k != r.end(); ++k)
            joint_offends[k] = !junctions[k]->joint.empty() && overlaps(index, junctions[k]->joint);
    });
    std::set<uint32_t> offending;
    for (uint32_t e = 0; e < graph.edges.size(); ++e)
        if (quad_offends[e]) offending.insert(e);
    for (size_t k = 0; k < junctions.size(); ++k)
        if (joint_offends[k])
            for (const NodeLayout::End& end : junctions[k]->ends) offending.insert(end.edge);
    return offending;
}

// The graph and layout without the edges `keep` leaves out, indices renumbered.
NarrowedRoads without_dropped(const RoadGraph& graph, RoadLayout layout, const std::vector<char>& keep) {
    NarrowedRoads out;
    std::vector<uint32_t> index(graph.edges.size(), 0);
    for (size_t e = 0; e < graph.edges.size(); ++e) {
        if (!keep[e]) continue;
        index[e] = static_cast<uint32_t>(out.graph.edges.size());
        out.graph.edges.push_back(graph.edges[e]);
        out.layout.from_cut.push_back(layout.from_cut[e]);
        out.layout.to_cut.push_back(layout.to_cut[e]);
        out.layout.quads.push_back(std::move(layout.quads[e]));
        out.layout.absorbed.push_back(layout.absorbed[e]);
    }
    out.layout.nodes = std::move(layout.nodes);
    for (NodeLayout& node : out.layout.nodes)
        for (NodeLayout::End& end : node.ends) end.edge = index[end.edge];
    return out;
}

}  // namespace

NarrowedRoads narrow_roads(RoadGraph graph, const std::vector<Building>& buildings,
                           const RoadParams& params, ParseReport& report) {
    const BuildingIndex index(buildings);
    // Per edge (char, not bool: edges are narrowed in parallel).
    std::vector<char> keep(graph.edges.size(), true), narrowed(graph.edges.size(), false);
    auto narrow = [&](size_t e) {
        graph.edges[e].width *= kNarrowStep;
        narrowed[e] = true;
        if (graph.edges[e].width < std::max(params.min_width, kNarrowestRoad)) keep[e] = false;
    };

    // 1. The edge's whole rectangle. Edges are independent here.
    tbb::parallel_for(tbb::blocked_range<size_t>(0, graph.edges.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t e = r.begin(); e != r.end(); ++e) {
            const RoadGraphEdge& edge = graph.edges[e];
            while (keep[e]) {
                const double h = 0.5 * edge.width;
                if (!overlaps(index, quad_for_cuts(edge, {h, h}, {}, {}))) break;
                narrow(e);
            }
        }
    });
    {
        RoadGraph kept;
        std::vector<char> kept_narrowed;
        kept.edges.reserve(static_cast<size_t>(std::count(keep.begin(), keep.end(), true)));
        for (size_t e = 0; e < graph.edges.size(); ++e) {
            if (!keep[e]) continue;
            kept.edges.push_back(graph.edges[e]);
            kept_narrowed.push_back(narrowed[e]);
        }
        for (bool k : keep)
            if (!k) report.dropped(ReportKind::RoadEdges, ReportReason::NarrowerThanMinWidth);
        graph = std::move(kept);
        narrowed = std::move(kept_narrowed);
        keep.assign(graph.edges.size(), true);
    }

    // 2. Miters and joints reach beyond the rectangles: the layout, made once, is checked
    // piece by piece. After the first round only pieces at nodes whose edges were
    // narrowed are checked again, and only what those edges change is laid out again.
    LayoutState layout(graph, carriageway_widths(graph), params.miter_limit);
    lay_out_all(layout);
    std::set<int64_t> dirty;
    for (int round = 0; round < kLayoutRounds; ++round) {
        const std::set<uint32_t> offending = offending_edges(layout, index, round == 0 ? nullptr : &dirty);
        if (offending.empty()) break;
        dirty.clear();
        for (uint32_t e : offending) {
            narrow(e);
            const double h = 0.5 * graph.edges[e].width;
            layout.widths[e] = {h, h};
            layout.removed[e] = !keep[e];
            dirty.insert(graph.edges[e].from_node);
            dirty.insert(graph.edges[e].to_node);
        }
        // A narrowed edge also changes the merged junction its node belongs to.
        for (const NodeLayout* junction : junctions_of(layout, dirty)) {
            dirty.insert(junction->node);
            dirty.insert(junction->members.begin(), junction->members.end());
        }
        update_layout(layout, std::vector<uint32_t>(offending.begin(), offending.end()));
    }
    int64_t count = 0;
    for (size_t e = 0; e < graph.edges.size(); ++e) {
        if (!keep[e]) report.dropped(ReportKind::RoadEdges, ReportReason::NarrowerThanMinWidth);
        count += narrowed[e] && keep[e];
    }
    if (count) report.note(ReportKind::RoadEdges, ReportReason::NarrowedBesideBuilding, count);
    return without_dropped(graph, take_layout(std::move(layout)), keep);
}

}  // namespace citygen
