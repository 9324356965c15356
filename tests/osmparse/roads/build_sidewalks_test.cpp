// Sidewalks (osmparse/roads/build_sidewalks.cpp) reuse the carriageway's layout: the
// outline is shaped on the same nodes and joins, and the pieces fill the band between.
#include "osmparse/polygons/ring_is_simple.h"
#include "osmparse/roads/build_sidewalks.h"
#include "tests/osmparse/roads/road_cases.h"

namespace citygen {
namespace {

using namespace road_cases;

RoadGraph t_junction() {
    RoadGraph g;
    g.edges.push_back(edge(1, 2, {0, 0}, {40, 0}, 8));
    g.edges.push_back(edge(1, 3, {0, 0}, {-40, 0}, 8));
    g.edges.push_back(edge(1, 4, {0, 0}, {0, 40}, 6));
    g.edges.push_back(edge(4, 5, {0, 40}, {20, 60}, 6));  // and a bend (miter) at node 4
    return g;
}

TEST(Sidewalks, OutlineFollowsTheCarriagewayLayout) {
    const RoadGraph g = t_junction();
    const RoadLayout carriageway = lay_out(g);
    std::vector<SideWidths> outer = carriageway_widths(g);
    for (SideWidths& w : outer) w.left += 2, w.right += 2;
    const RoadLayout outline = lay_out_outline(g, carriageway, outer, kMiterLimit);
    ASSERT_EQ(outline.nodes.size(), carriageway.nodes.size());
    for (size_t k = 0; k < outline.nodes.size(); ++k) {
        const NodeLayout &o = outline.nodes[k], &c = carriageway.nodes[k];
        EXPECT_EQ(o.node, c.node);
        EXPECT_EQ(o.kind, c.kind);
        ASSERT_EQ(o.ends.size(), c.ends.size());
        for (size_t i = 0; i < o.ends.size(); ++i) EXPECT_EQ(o.ends[i].edge, c.ends[i].edge);
    }
    expect_joint_meets_quads(outline, node_of(outline, 1));
    // The outline lies around the carriageway: its joint covers the carriageway's.
    const Ring& inner_joint = node_of(carriageway, 1).joint;
    EXPECT_NEAR(clipped_area(inner_joint, node_of(outline, 1).joint), signed_area(inner_joint), 1e-6);
}

TEST(Sidewalks, PiecesFillTheBandBesideTheCarriageway) {
    const RoadGraph g = t_junction();
    ParseReport report;
    RoadSurface surface = build_road_polygons(g, lay_out(g), report);
    SidewalkParams params;
    const std::vector<Sidewalk> walks = build_sidewalks(g, surface, {}, params, kMiterLimit, report);
    int strips = 0, corners = 0;
    double area = 0;
    for (const Sidewalk& s : walks) {
        (s.kind == SidewalkKind::Strip ? strips : corners)++;
        area += signed_area(s.polygon);
        EXPECT_GT(signed_area(s.polygon), 0);
        EXPECT_TRUE(ring_is_simple(s.polygon));
        // Off the carriageway, and never further from it than the sidewalk is wide (the
        // outer corner of the 45-degree miter at node 4 by 1 / cos(22.5 deg)).
        for (const RoadEdge& r : surface.roads) EXPECT_LT(clipped_area(s.polygon, r.quad), 0.01);
        for (const Joint& j : surface.joints) EXPECT_LT(clipped_area(s.polygon, j.polygon), 0.01);
        for (Vec2 p : s.polygon) {
            double nearest = 1e300;
            for (const RoadEdge& r : surface.roads) nearest = std::min(nearest, distance_to_boundary(p, r.quad));
            for (const Joint& j : surface.joints) nearest = std::min(nearest, distance_to_boundary(p, j.polygon));
            EXPECT_LE(nearest, params.width / std::cos(kPi / 8) + 1e-6) << p.x << "," << p.y;
        }
    }
    EXPECT_EQ(strips, 8);   // both sides of four edges
    EXPECT_GE(corners, 3);  // the T's two corners and its straight side (cut in two)
    // Roughly 2 m along both sides of 40 + 40 + 40 + 28 m of road, less the junction.
    EXPECT_GT(area, 2 * 2 * 120);
    EXPECT_LT(area, 2 * 2 * 150);
    EXPECT_EQ(report.kept_count(ReportKind::SidewalkSides), 8);
}

}  // namespace
}  // namespace citygen
