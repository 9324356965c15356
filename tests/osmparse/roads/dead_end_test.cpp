// Dead ends (osmparse/roads/dead_end.cpp): the quad ends square at the node.
#include "tests/osmparse/roads/road_cases.h"

namespace citygen {
namespace {

using namespace road_cases;

TEST(DeadEnd, ALoneEdgeIsItsRectangle) {
    RoadGraph g;
    g.edges.push_back(edge(1, 2, {0, 0}, {20, 0}, 6));
    const RoadLayout layout = lay_out(g);
    ASSERT_EQ(layout.nodes.size(), 2u);
    for (const NodeLayout& node : layout.nodes) {
        EXPECT_EQ(node.kind, JoinKind::End);
        EXPECT_TRUE(node.joint.empty());
    }
    const Ring expected{{0, -3}, {20, -3}, {20, 3}, {0, 3}};
    ASSERT_EQ(layout.quads[0].size(), 4u);
    for (int i = 0; i < 4; ++i) {
        EXPECT_NEAR(layout.quads[0][i].x, expected[i].x, 1e-12) << i;
        EXPECT_NEAR(layout.quads[0][i].y, expected[i].y, 1e-12) << i;
    }
}

TEST(DeadEnd, ArmOfAJunctionEndsSquare) {
    // A T whose arms end freely: each free end is cut square through its node, the
    // junction end is not.
    RoadGraph g;
    g.edges.push_back(edge(1, 2, {0, 0}, {30, 0}, 6));
    g.edges.push_back(edge(1, 3, {0, 0}, {-30, 0}, 6));
    g.edges.push_back(edge(1, 4, {0, 0}, {0, 30}, 4));
    const RoadLayout layout = lay_out(g);
    expect_quads_keep_width(g, layout);
    for (uint32_t e = 0; e < 3; ++e) {
        EXPECT_EQ(node_of(layout, g.edges[e].to_node).kind, JoinKind::End);
        EXPECT_EQ(layout.to_cut[e].t_left, 0);
        EXPECT_EQ(layout.to_cut[e].t_right, 0);
        const auto [right, left] = end_corners(layout.quads[e], false);
        EXPECT_NEAR(dot(right - g.edges[e].to, normalize(g.edges[e].to - g.edges[e].from)), 0, 1e-9);
        EXPECT_NEAR(dot(left - g.edges[e].to, normalize(g.edges[e].to - g.edges[e].from)), 0, 1e-9);
    }
    EXPECT_GT(layout.from_cut[2].t_left, 0);  // the side road gives way to the junction
}

}  // namespace
}  // namespace citygen
