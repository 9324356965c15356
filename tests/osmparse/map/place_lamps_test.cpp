// Street lamps: tagged ones kept (moved off the road surface when our width covers
// them), generated ones at the spacing, on alternating sides, never on a road or in a
// building, never near a tagged lamp.
#include <gtest/gtest.h>

#include "osmparse/map/place_lamps.h"
#include "osmparse/polygons/polygon_overlap.h"

using namespace citygen;

namespace {

// A straight 200 m road, 6 m wide, along the x axis through the projection's origin.
Scene straight_road_scene() {
    Scene s;
    RoadEdge r;
    r.osm = {OsmType::Way, 7};
    r.from_node = 1;
    r.to_node = 2;
    r.centreline = {{-100, 0}, {100, 0}};
    r.quad = {{-100, -3}, {100, -3}, {100, 3}, {-100, 3}};
    r.width = 6;
    s.roads.push_back(r);
    return s;
}

OsmNode lamp_node(const Projection& p, int64_t id, Vec2 at) {
    OsmNode n;
    n.id = id;
    p.to_wgs84(at, n.location.lat, n.location.lon);
    n.tags.entries = {{"highway", "street_lamp"}};
    return n;
}

}  // namespace

TEST(PlaceLamps, GeneratedAtTheSpacingOnAlternatingSidesOffTheRoad) {
    const Projection projection(43.7, 7.4);
    Scene scene = straight_road_scene();
    LampParams params;
    ParseReport report;
    const std::vector<Lamp> lamps = place_lamps(OsmData{}, projection, scene, params, 1, report);
    // 200 m at 28 m: 7 or 8 lamps depending on the seeded phase.
    EXPECT_GE(lamps.size(), 7u);
    EXPECT_LE(lamps.size(), 8u);
    int left = 0;
    for (size_t i = 0; i < lamps.size(); ++i) {
        const Lamp& l = lamps[i];
        EXPECT_EQ(l.source, LampSource::Generated);
        EXPECT_EQ(l.osm.id, 7);
        EXPECT_NEAR(std::fabs(l.position.y), 3.5, 1e-9);  // 0.5 m beyond the kerb
        EXPECT_FALSE(point_in_ring({l.position.x, l.position.y}, scene.roads[0].quad));
        left += l.position.y > 0;
        if (i > 0) {
            EXPECT_NEAR(l.position.x - lamps[i - 1].position.x, params.spacing, 1e-6);
            EXPECT_NE(l.position.y > 0, lamps[i - 1].position.y > 0) << "sides alternate";
        }
    }
    EXPECT_GE(left, 3);
}

TEST(PlaceLamps, TaggedLampsMovedOffTheRoadAndKeptClearOf) {
    const Projection projection(43.7, 7.4);
    Scene scene = straight_road_scene();
    OsmData osm;
    osm.street_lamps.push_back(lamp_node(projection, 5, {0, 2.0}));     // on our road surface
    osm.street_lamps.push_back(lamp_node(projection, 6, {50, 10.0}));   // beside it
    LampParams params;
    ParseReport report;
    const std::vector<Lamp> lamps = place_lamps(osm, projection, scene, params, 1, report);
    ASSERT_GE(lamps.size(), 2u);
    EXPECT_EQ(lamps[0].source, LampSource::Tagged);
    EXPECT_EQ(lamps[0].osm.id, 5);
    EXPECT_NEAR(lamps[0].position.y, 3.5, 1e-3) << "pushed just off the road edge";
    EXPECT_NEAR(lamps[1].position.y, 10.0, 1e-3);
    EXPECT_EQ(report.note_count(ReportKind::TaggedStreetLamps, ReportReason::MovedOffRoad), 1);
    for (size_t i = 2; i < lamps.size(); ++i) {
        const Vec2 p{lamps[i].position.x, lamps[i].position.y};
        EXPECT_GE(length(p - Vec2(0, 3.5)), params.min_distance_to_tagged);
        EXPECT_GE(length(p - Vec2(50, 10)), params.min_distance_to_tagged);
    }
}

TEST(PlaceLamps, NeverInsideABuilding) {
    const Projection projection(43.7, 7.4);
    Scene scene = straight_road_scene();
    Building b;
    b.osm = {OsmType::Way, 99};
    b.outer = {{-100, 3.2}, {100, 3.2}, {100, 20}, {-100, 20}};  // the whole north side
    scene.buildings.push_back(b);
    OsmData osm;
    osm.street_lamps.push_back(lamp_node(projection, 5, {10, 8}));  // mapped inside it
    ParseReport report;
    const std::vector<Lamp> lamps = place_lamps(osm, projection, scene, LampParams{}, 1, report);
    EXPECT_EQ(report.dropped_count(ReportKind::TaggedStreetLamps, ReportReason::InsideRoadOrBuilding), 1);
    ASSERT_FALSE(lamps.empty());
    for (const Lamp& l : lamps) EXPECT_LT(l.position.y, 0) << "only the south side is free";
}
