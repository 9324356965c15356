// Narrowing beside buildings (osmparse/roads/narrow_roads.cpp) and the layout update it
// relies on (update_layout in road_layout.cpp): only what the narrowed edges change is
// laid out again, and the result is the layout a fresh start would give.
#include <random>
#include <set>

#include "osmparse/roads/layout_state.h"
#include "osmparse/roads/narrow_roads.h"
#include "tests/osmparse/roads/road_cases.h"

namespace citygen {
namespace {

using namespace road_cases;

void expect_same_layout(const RoadLayout& a, const RoadLayout& b) {
    ASSERT_EQ(a.quads.size(), b.quads.size());
    for (size_t e = 0; e < a.quads.size(); ++e) {
        EXPECT_EQ(a.quads[e], b.quads[e]) << "edge " << e;
        EXPECT_EQ(a.absorbed[e], b.absorbed[e]) << "edge " << e;
    }
    ASSERT_EQ(a.nodes.size(), b.nodes.size());
    for (size_t k = 0; k < a.nodes.size(); ++k) {
        EXPECT_EQ(a.nodes[k].node, b.nodes[k].node);
        EXPECT_EQ(a.nodes[k].kind, b.nodes[k].kind) << "node " << a.nodes[k].node;
        EXPECT_EQ(a.nodes[k].members, b.nodes[k].members) << "node " << a.nodes[k].node;
        EXPECT_EQ(a.nodes[k].joint, b.nodes[k].joint) << "node " << a.nodes[k].node;
    }
}

// A 90-degree bend at node 2 (0, 0) whose miter's outer corner reaches towards a
// building at x, y in [3, 10] x [-10, -3] (the edges' rectangles stay clear of it), and
// further on a bend at node 3 and a cross at node 4 far from the building.
RoadGraph bend_beside_building() {
    RoadGraph g;
    g.edges.push_back(edge(1, 2, {-60, 0}, {0, 0}, 8));
    g.edges.push_back(edge(2, 3, {0, 0}, {0, 60}, 8));
    g.edges.push_back(edge(3, 4, {0, 60}, {200, 60}, 8));
    g.edges.push_back(edge(4, 5, {200, 60}, {200, 0}, 8));
    g.edges.push_back(edge(4, 6, {200, 60}, {260, 60}, 8));
    g.edges.push_back(edge(4, 7, {200, 60}, {200, 120}, 8));
    return g;
}

std::vector<Building> the_building() {
    Building b;
    b.osm = {OsmType::Way, 99};
    b.outer = {{3, -10}, {10, -10}, {10, -3}, {3, -3}};
    b.height = 10;
    return {b};
}

TEST(NarrowBesideBuilding, OnlyTheEdgesAtTheTouchedJunctionNarrow) {
    const RoadGraph graph = bend_beside_building();
    ParseReport report;
    const NarrowedRoads narrowed = narrow_roads(graph, the_building(), RoadParams{}, report);
    ASSERT_EQ(narrowed.graph.edges.size(), graph.edges.size());
    // The two edges at the bend lose width until the miter clears the building ...
    EXPECT_LT(narrowed.graph.edges[0].width, 8);
    EXPECT_LT(narrowed.graph.edges[1].width, 8);
    EXPECT_GT(narrowed.graph.edges[0].width, 5.7);  // two steps of 15%: 5.78 m
    EXPECT_EQ(report.note_count(ReportKind::RoadEdges, ReportReason::NarrowedBesideBuilding), 2);
    // ... every other edge keeps its width, and the far cross its joint.
    for (size_t e = 2; e < graph.edges.size(); ++e) EXPECT_EQ(narrowed.graph.edges[e].width, 8) << e;
    const RoadLayout untouched = lay_out(graph);
    EXPECT_EQ(node_of(narrowed.layout, 4).joint, node_of(untouched, 4).joint);
    expect_joint_meets_quads(narrowed.layout, node_of(narrowed.layout, 4));
    // Nothing overlaps the building any more.
    const BuildingIndex index(the_building());
    for (const Ring& q : narrowed.layout.quads) {
        double largest = 0;
        index.overlap(q, &largest);
        EXPECT_LE(largest, kRoadBuildingOverlapTolerance);
    }
    // The layout kept up to date while narrowing is the one a fresh start gives.
    expect_same_layout(narrowed.layout, lay_out(narrowed.graph));
    expect_quads_keep_width(narrowed.graph, narrowed.layout);
}

// A main road along y = 0 with a T junction every 50 m (nodes 1..6, side roads north).
RoadGraph row_of_junctions() {
    RoadGraph g;
    for (int64_t i = 1; i < 6; ++i) g.edges.push_back(edge(i, i + 1, {50.0 * i, 0}, {50.0 * (i + 1), 0}, 8));
    for (int64_t i = 1; i <= 6; ++i) g.edges.push_back(edge(i, 100 + i, {50.0 * i, 0}, {50.0 * i, 40}, 6));
    g.edges.push_back(edge(0, 1, {0, 0}, {50, 0}, 8));
    g.edges.push_back(edge(6, 7, {300, 0}, {350, 0}, 8));
    return g;
}

TEST(NarrowBesideBuilding, UpdateReshapesOnlyAroundTheChangedEdge) {
    RoadGraph graph = row_of_junctions();
    LayoutState state(graph, carriageway_widths(graph), kMiterLimit);
    lay_out_all(state);
    const RoadLayout before = assemble_layout(state);
    // Narrow the side road at junction 3 (edge 7: 3 -> 103).
    const uint32_t side = 7;
    ASSERT_EQ(graph.edges[side].from_node, 3);
    graph.edges[side].width = 4;
    state.widths[side] = {2, 2};
    const std::set<int64_t> refinished = update_layout(state, {side});
    const RoadLayout after = assemble_layout(state);
    // Junction 3 changes, and its neighbours along the main road get their share of
    // the edges between them again; junctions further away are not laid out again.
    EXPECT_TRUE(refinished.count(3));
    for (int64_t far : {1, 5, 6}) EXPECT_FALSE(refinished.count(far)) << far;
    EXPECT_NE(node_of(after, 3).joint, node_of(before, 3).joint);
    for (int64_t far : {1, 5, 6}) EXPECT_EQ(node_of(after, far).joint, node_of(before, far).joint);
    expect_same_layout(after, lay_out(graph));
    expect_joint_meets_quads(after, node_of(after, 3));
}

// A tangle: a jittered grid of nodes 8-20 m apart with diagonals, widths 4-12 m, so
// junctions merge, miters turn into joints and short edges are shared out.
RoadGraph tangle(std::mt19937& rng) {
    std::uniform_real_distribution<double> jitter(-4, 4), width(4, 12), coin(0, 1);
    const int n = 7;
    std::vector<Vec2> at;
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) at.push_back({14.0 * x + jitter(rng), 14.0 * y + jitter(rng)});
    RoadGraph g;
    auto link = [&](int a, int b) { g.edges.push_back(edge(a + 1, b + 1, at[a], at[b], width(rng))); };
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const int i = y * n + x;
            if (x + 1 < n && coin(rng) < 0.8) link(i, i + 1);
            if (y + 1 < n && coin(rng) < 0.8) link(i, i + n);
            if (x + 1 < n && y + 1 < n && coin(rng) < 0.2) link(i, i + n + 1);
        }
    return g;
}

TEST(NarrowBesideBuilding, UpdatesMatchAFreshLayoutInATangle) {
    // Narrowing edge after edge, the updated layout must stay the one a fresh start gives
    // (each update lays out again only what depends on the narrowed edge).
    std::mt19937 rng(12);
    RoadGraph graph = tangle(rng);
    LayoutState state(graph, carriageway_widths(graph), kMiterLimit);
    lay_out_all(state);
    const RoadLayout first = assemble_layout(state);
    int merged = 0;
    for (const NodeLayout& node : first.nodes) merged += !node.members.empty();
    EXPECT_GT(merged, 0) << "the tangle should have merged junctions";
    std::uniform_int_distribution<uint32_t> pick(0, static_cast<uint32_t>(graph.edges.size() - 1));
    for (int step = 0; step < 40; ++step) {
        std::vector<uint32_t> changed{pick(rng), pick(rng)};
        for (uint32_t e : changed) {
            graph.edges[e].width *= 0.85;
            state.widths[e] = {0.5 * graph.edges[e].width, 0.5 * graph.edges[e].width};
        }
        update_layout(state, changed);
        SCOPED_TRACE(step);
        expect_same_layout(assemble_layout(state), lay_out(graph));
        if (HasFailure()) break;
    }
}

TEST(NarrowBesideBuilding, RemovingAnEdgeMatchesAFreshLayout) {
    RoadGraph graph = row_of_junctions();
    LayoutState state(graph, carriageway_widths(graph), kMiterLimit);
    lay_out_all(state);
    const uint32_t side = 7;  // junction 3 becomes a straight degree-2 node
    state.removed[side] = true;
    update_layout(state, {side});
    const RoadLayout after = assemble_layout(state);
    EXPECT_EQ(node_of(after, 3).kind, JoinKind::Miter);
    EXPECT_TRUE(node_of(after, 3).joint.empty());
    EXPECT_TRUE(after.quads[side].empty());
    // The same as laying out the graph without that edge (indices shift past it).
    RoadGraph without = graph;
    without.edges.erase(without.edges.begin() + side);
    const RoadLayout fresh = lay_out(without);
    for (uint32_t e = 0, f = 0; e < graph.edges.size(); ++e) {
        if (e == side) continue;
        EXPECT_EQ(after.quads[e], fresh.quads[f]) << e;
        ++f;
    }
    ASSERT_EQ(after.nodes.size(), fresh.nodes.size());
    for (size_t k = 0; k < fresh.nodes.size(); ++k) EXPECT_EQ(after.nodes[k].joint, fresh.nodes[k].joint);
}

}  // namespace
}  // namespace citygen
