// Miters (osmparse/roads/miter.cpp): at a degree-2 node the two quads meet on one line.
#include "tests/osmparse/roads/road_cases.h"

namespace citygen {
namespace {

using namespace road_cases;

RoadGraph bend(double turn_deg, double width = 6) {
    const double a = turn_deg * kPi / 180;
    RoadGraph g;
    g.edges.push_back(edge(1, 2, {-20, 0}, {0, 0}, width));
    g.edges.push_back(edge(2, 3, {0, 0}, {20 * std::cos(a), 20 * std::sin(a)}, width));
    return g;
}

void expect_meet_on_miter(const RoadGraph& g, const RoadLayout& layout) {
    const Ring &a = layout.quads[0], &b = layout.quads[1];
    ASSERT_EQ(a.size(), 4u);
    ASSERT_EQ(b.size(), 4u);
    // Edge 0 arrives (its `to` end), edge 1 leaves (its `from` end): right side to right side.
    EXPECT_NEAR(length(a[1] - b[0]), 0, 1e-9);
    EXPECT_NEAR(length(a[2] - b[3]), 0, 1e-9);
    EXPECT_LT(clipped_area(a, b), 1e-6);
    expect_quads_keep_width(g, layout);
}

TEST(Miter, GentleBendMeetsEdgeToEdge) {
    for (double turn : {10.0, 30.0, 60.0, -45.0}) {
        SCOPED_TRACE(turn);
        const RoadGraph g = bend(turn);
        const RoadLayout layout = lay_out(g);
        EXPECT_EQ(node_of(layout, 2).kind, JoinKind::Miter);
        EXPECT_TRUE(node_of(layout, 2).joint.empty());
        expect_meet_on_miter(g, layout);
    }
}

TEST(Miter, StraightOnIsCutSquare) {
    const RoadGraph g = bend(0);
    const RoadLayout layout = lay_out(g);
    EXPECT_EQ(node_of(layout, 2).kind, JoinKind::Miter);
    EXPECT_EQ(layout.to_cut[0].t_left, 0);
    EXPECT_EQ(layout.from_cut[1].t_right, 0);
    expect_meet_on_miter(g, layout);
}

TEST(Miter, SharpTurnBecomesAJunction) {
    // Beyond the miter limit the outer corner would reach far out: a joint instead.
    const RoadGraph g = bend(130);
    const RoadLayout layout = lay_out(g);
    const NodeLayout& node = node_of(layout, 2);
    EXPECT_EQ(node.kind, JoinKind::Joint);
    expect_joint_meets_quads(layout, node);
}

}  // namespace
}  // namespace citygen
