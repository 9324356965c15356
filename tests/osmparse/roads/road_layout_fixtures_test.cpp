// Hand-made road fixtures (tests/data/road_*.osm, written by make_road_fixtures.py):
// every quad convex, every joint simple, quads ending exactly on their joint's boundary
// without overlapping it, nothing inside a building, plus what each shape must give.
#include <gtest/gtest.h>

#include "osmparse/pipeline.h"
#include "tests/osmparse/parse_quietly.h"
#include "tests/osmparse/roads/road_checks.h"

using namespace citygen;
using citygen::test::parse_quietly;

namespace {

Scene parse_fixture(const std::string& name, bool strict_joins = true) {
    ParseReport report;
    Scene scene = parse_quietly(std::string(CITYGEN_SOURCE_DIR) + "/tests/data/road_" + name + ".osm", report);
    check_road_network(scene, strict_joins);
    return scene;
}

double total_area(const Scene& s) {
    double a = 0;
    for (const RoadEdge& r : s.roads) a += signed_area(r.quad);
    for (const Joint& j : s.joints) a += signed_area(j.polygon);
    return a;
}

size_t count_kind(const Scene& s, SidewalkKind k) {
    size_t n = 0;
    for (const Sidewalk& w : s.sidewalks) n += w.kind == k;
    return n;
}

}  // namespace

TEST(RoadFixtures, StraightRoadIsOneMergedQuad) {
    const Scene s = parse_fixture("straight");
    ASSERT_EQ(s.roads.size(), 1u);
    EXPECT_TRUE(s.joints.empty());
    // Residential default 6 m; the fixture's metres are approximate to 0.3%.
    EXPECT_NEAR(signed_area(s.roads[0].quad), 100 * 6.0, 2.0);
    EXPECT_EQ(count_kind(s, SidewalkKind::Strip), 2u);
    EXPECT_GE(s.lamps.size(), 2u);
    EXPECT_LE(s.lamps.size(), 5u);
}

TEST(RoadFixtures, BendMeetsOnTheMiter) {
    const Scene s = parse_fixture("bend");
    ASSERT_EQ(s.roads.size(), 2u);
    EXPECT_TRUE(s.joints.empty());
    // Edge 0 ends where edge 1 starts: its end corners are edge 1's start corners.
    const Ring &a = s.roads[0].quad, &b = s.roads[1].quad;
    EXPECT_LT(length(a[1] - b[0]), 0.01);
    EXPECT_LT(length(a[2] - b[3]), 0.01);
    EXPECT_LT(clipped_area(a, b), 0.01);
}

TEST(RoadFixtures, TJunctionHasOneJointOfThree) {
    const Scene s = parse_fixture("t");
    ASSERT_EQ(s.joints.size(), 1u);
    EXPECT_EQ(s.joints[0].edges.size(), 3u);
    EXPECT_EQ(s.roads.size(), 3u);
}

TEST(RoadFixtures, CrossJointIsTheSquareBetweenTheRoads) {
    const Scene s = parse_fixture("cross");
    ASSERT_EQ(s.joints.size(), 1u);
    EXPECT_EQ(s.joints[0].edges.size(), 4u);
    EXPECT_NEAR(signed_area(s.joints[0].polygon), 36.0, 0.01);
    // Two 100 m x 6 m roads crossing: 2 * 600 - 36, covered once.
    EXPECT_NEAR(total_area(s), 1164.0, 4.0);
    EXPECT_EQ(count_kind(s, SidewalkKind::Strip), 8u);
    EXPECT_EQ(count_kind(s, SidewalkKind::Corner), 4u);
    // 2 m sidewalks: the outline is two 10 m wide roads crossing (2 * 1000 - 100 m^2),
    // the band is the outline minus the carriageways, corners 2 m x 2 m.
    double walk = 0;
    for (const Sidewalk& w : s.sidewalks) {
        walk += signed_area(w.polygon);
        if (w.kind == SidewalkKind::Corner) {
            EXPECT_NEAR(signed_area(w.polygon), 4.0, 0.05);
        }
        EXPECT_DOUBLE_EQ(w.curb_height, 0.15);
    }
    EXPECT_NEAR(walk, 1900.0 - 1164.0, 4.0);
}

TEST(RoadFixtures, FiveWayStar) {
    const Scene s = parse_fixture("star5");
    ASSERT_EQ(s.joints.size(), 1u);
    EXPECT_EQ(s.joints[0].edges.size(), 5u);
    // Neighbouring offset lines meet 3 m / sin(36 deg) from the centre: a regular
    // pentagon of about 61.9 m^2 (up to 10 vertices where rounding splits corners).
    EXPECT_GE(s.joints[0].polygon.size(), 5u);
    EXPECT_LE(s.joints[0].polygon.size(), 10u);
    EXPECT_NEAR(signed_area(s.joints[0].polygon), 61.9, 1.5);
}

TEST(RoadFixtures, RoundaboutRingAndFourEntries) {
    const Scene s = parse_fixture("roundabout");
    EXPECT_EQ(s.roads.size(), 16u);
    EXPECT_EQ(s.joints.size(), 4u);
    for (const Joint& j : s.joints) EXPECT_EQ(j.edges.size(), 3u);
}

TEST(RoadFixtures, DeadEndEndsSquare) {
    const Scene s = parse_fixture("dead_end");
    ASSERT_EQ(s.joints.size(), 1u);
    for (const RoadEdge& r : s.roads)
        if (r.road_class == RoadClass::Service) {
            EXPECT_EQ(r.to_joint, -1);
            EXPECT_NEAR(std::fabs(signed_area(r.quad)), (20 - 3.0) * 3.5, 0.2);  // cut back to the street's edge
        }
}

TEST(RoadFixtures, JunctionsCloserThanTheirRoadsAreWideMerge) {
    // The two junctions are 3 m apart on a 9 m primary road with 6 m side streets: one
    // joint covers both, the 3 m edge is absorbed, and the strict checks hold.
    const Scene s = parse_fixture("short_edge");
    ASSERT_EQ(s.joints.size(), 1u);
    EXPECT_EQ(s.joints[0].edges.size(), 4u);
    EXPECT_EQ(s.roads.size(), 4u);
    for (const RoadEdge& r : s.roads) EXPECT_GT(length(r.centreline[1] - r.centreline[0]), 4);
    auto covered = [&](Vec2 p) {
        for (const RoadEdge& r : s.roads)
            if (point_in_ring(p, r.quad)) return true;
        for (const Joint& j : s.joints)
            if (point_in_ring(p, j.polygon)) return true;
        return false;
    };
    // No hole anywhere between both side streets and the primary's edges (local metres:
    // the fixture's junction nodes are the west end of road 2 and the east end of road 0).
    const Vec2 west = s.roads[0].centreline[1], east = s.roads[1].centreline[0];
    const Vec2 along = normalize(east - west), across = perp_left(along);
    for (double x = -2.9; x <= length(east - west) + 2.9; x += 0.1)
        for (double y = -4.4; y <= 4.4; y += 0.1)
            EXPECT_TRUE(covered(west + along * x + across * y)) << x << "," << y;
}

TEST(RoadFixtures, NearlyParallelRoadsGiveASimpleJoint) {
    const Scene s = parse_fixture("near_parallel");
    ASSERT_EQ(s.joints.size(), 1u);
    EXPECT_EQ(s.roads.size(), 3u);
}

TEST(RoadFixtures, RoadBrushingABuildingIsNarrowed) {
    const Scene s = parse_fixture("brushing_building");
    ASSERT_EQ(s.roads.size(), 1u);
    ASSERT_EQ(s.buildings.size(), 1u);
    EXPECT_LT(s.roads[0].width, 4.0);   // its edge must stay south of y = 2
    EXPECT_GE(s.roads[0].width, 2.0);   // but it is not dropped
    EXPECT_LT(overlap_area(s.roads[0].quad, s.buildings[0]), 0.01);
    // Only the side away from the building keeps a sidewalk.
    EXPECT_EQ(count_kind(s, SidewalkKind::Strip), 1u);
}
