// Junctions (osmparse/roads/junction.cpp, finished in finish_joint.cpp): T, cross and
// near-parallel neighbours.
#include "tests/osmparse/roads/road_cases.h"

namespace citygen {
namespace {

using namespace road_cases;

// Arms leaving node 1 at (0, 0) in the given directions (degrees) and widths.
RoadGraph star(const std::vector<std::pair<double, double>>& arms) {
    RoadGraph g;
    int64_t next = 2;
    for (auto [deg, width] : arms) {
        const double a = deg * kPi / 180;
        g.edges.push_back(edge(1, next++, {0, 0}, {40 * std::cos(a), 40 * std::sin(a)}, width));
    }
    return g;
}

TEST(Junction, TJunction) {
    const RoadGraph g = star({{0, 8}, {180, 8}, {90, 5}});
    const RoadLayout layout = lay_out(g);
    const NodeLayout& node = node_of(layout, 1);
    EXPECT_EQ(node.ends.size(), 3u);
    expect_joint_meets_quads(layout, node);
    expect_quads_keep_width(g, layout);
    EXPECT_TRUE(point_in_ring({0, 0}, node.joint));
    // The side road is cut back to the main road's kerb; the main road only as far as
    // the side road's corners reach.
    EXPECT_NEAR(layout.from_cut[2].t_left, 4, 1e-9);
    EXPECT_NEAR(layout.from_cut[0].t_left, 2.5, 1e-9);
}

TEST(Junction, Cross) {
    const RoadGraph g = star({{0, 6}, {90, 6}, {180, 6}, {270, 6}});
    const RoadLayout layout = lay_out(g);
    const NodeLayout& node = node_of(layout, 1);
    EXPECT_EQ(node.ends.size(), 4u);
    expect_joint_meets_quads(layout, node);
    expect_quads_keep_width(g, layout);
    EXPECT_NEAR(signed_area(node.joint), 36, 1e-9);  // the 6 m x 6 m square between the kerbs
}

TEST(Junction, NearParallelNeighboursShareACut) {
    // A fork of 8 degrees: the corner lies far out, so both quads start on one line.
    const RoadGraph g = star({{0, 6}, {8, 6}, {180, 6}});
    const RoadLayout layout = lay_out(g);
    const NodeLayout& node = node_of(layout, 1);
    expect_joint_meets_quads(layout, node);
    expect_quads_keep_width(g, layout);
    // The joint stays near the node instead of reaching to where the kerbs meet (~43 m).
    for (Vec2 p : node.joint) EXPECT_LT(length(p), 25);
}

}  // namespace
}  // namespace citygen
