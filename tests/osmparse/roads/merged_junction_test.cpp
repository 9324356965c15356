// Merged junctions (osmparse/roads/merged_junction.cpp): junctions closer together than
// their roads are wide become one joint; the short edge between them is absorbed.
#include "tests/osmparse/roads/road_cases.h"

namespace citygen {
namespace {

using namespace road_cases;

// A main road (10 m) along y = 0 with side roads (6 m) leaving north at x = 0 (node 1)
// and south at x = `gap` (node 2).
RoadGraph staggered(double gap) {
    RoadGraph g;
    g.edges.push_back(edge(10, 1, {-40, 0}, {0, 0}, 10));
    g.edges.push_back(edge(1, 2, {0, 0}, {gap, 0}, 10));
    g.edges.push_back(edge(2, 11, {gap, 0}, {gap + 40, 0}, 10));
    g.edges.push_back(edge(1, 12, {0, 0}, {0, 40}, 6));
    g.edges.push_back(edge(2, 13, {gap, 0}, {gap, -40}, 6));
    return g;
}

TEST(MergedJunction, CloseJunctionsBecomeOne) {
    const RoadGraph g = staggered(3);
    const RoadLayout layout = lay_out(g);
    EXPECT_TRUE(layout.absorbed[1]);
    EXPECT_TRUE(layout.quads[1].empty());
    const NodeLayout& merged = node_of(layout, 1);
    EXPECT_EQ(merged.members, (std::vector<int64_t>{1, 2}));
    EXPECT_EQ(merged.ends.size(), 4u);
    for (const NodeLayout& node : layout.nodes) EXPECT_NE(node.node, 2) << "member 2 stands alone too";
    EXPECT_NEAR(merged.position.x, 1.5, 1e-12);
    expect_joint_meets_quads(layout, merged);
    expect_quads_keep_width(g, layout);
    // The joint covers the absorbed edge's ground.
    EXPECT_TRUE(point_in_ring({1.5, 0}, merged.joint));
}

TEST(MergedJunction, JunctionsFarApartStayTwo) {
    const RoadGraph g = staggered(30);
    const RoadLayout layout = lay_out(g);
    EXPECT_FALSE(layout.absorbed[1]);
    for (int64_t id : {1, 2}) {
        const NodeLayout& node = node_of(layout, id);
        EXPECT_TRUE(node.members.empty());
        expect_joint_meets_quads(layout, node);
    }
    expect_quads_keep_width(g, layout);
}

}  // namespace
}  // namespace citygen
