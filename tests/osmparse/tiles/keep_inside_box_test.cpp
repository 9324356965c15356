// A tile keeps exactly the objects anchored in its core box; two tiles that share an edge keep
// every object once between them, and what refers to something keeps it (or says -1).
#include <gtest/gtest.h>

#include "common/error.h"
#include "osmparse/map/assemble_sea.h"
#include "osmparse/tiles/keep_inside_box.h"

using namespace citygen;

namespace {

const Projection kProjection(50, 8);
// West and east of the meridian 8°E, the whole world otherwise.
const LatLonBox kWest{{-90, -180}, {90, 8}}, kEast{{-90, 8}, {90, 180}};

Ring square(Vec2 c, double half) {
    return {{c.x - half, c.y - half}, {c.x + half, c.y - half}, {c.x + half, c.y + half}, {c.x - half, c.y + half}};
}

RoadEdge road(int64_t way, int64_t from, int64_t to, Vec2 a, Vec2 b) {
    RoadEdge r;
    r.osm = {OsmType::Way, way};
    r.from_node = from, r.to_node = to;
    r.centreline = {a, b};
    r.quad = {a, b, b + Vec2(0, 3), a + Vec2(0, 3)};
    return r;
}

// West: building 1, road 10 (-50..30), the joint at x = 30 (its first edge is road 10), the
// corner at that joint, the lamp. East: building 2, road 11 (30..100) with its strip and
// crossing, the tree, the land cover.
Scene two_sided_scene() {
    Scene s;
    Building west, east;
    west.osm = {OsmType::Way, 1}, west.outer = square({-100, 0}, 5);
    east.osm = {OsmType::Way, 2}, east.outer = square({100, 0}, 5);
    s.buildings = {west, east};
    s.roads = {road(10, 1, 2, {-50, 0}, {30, 0}), road(11, 2, 3, {30, 0}, {100, 0})};
    Joint j;
    j.osm = {OsmType::Node, 2};
    j.polygon = square({30, 0}, 4);
    j.edges = {0, 1};
    s.joints = {j};
    s.roads[0].to_joint = 0, s.roads[1].from_joint = 0;
    Sidewalk strip, corner;
    strip.polygon = square({65, 5}, 1), strip.road = 1;
    corner.kind = SidewalkKind::Corner, corner.polygon = square({33, 5}, 1), corner.road = 1, corner.joint = 0;
    s.sidewalks = {strip, corner};
    Crossing c;
    c.road = 1, c.position = {60, 0};
    s.crossings = {c};
    Lamp l;
    l.position = {-5, 4, 0};
    s.lamps = {l};
    Tree t;
    t.position = {5, 4};
    s.trees = {t};
    LandCover g;
    g.outer = square({200, 0}, 20);
    s.land_cover = {g};
    return s;
}

TEST(KeepInsideBox, EachTileKeepsItsSideAndRenumbers) {
    Scene west = two_sided_scene(), east = two_sided_scene();
    ParseReport report;
    keep_inside_box(west, kProjection, kWest, report);
    keep_inside_box(east, kProjection, kEast, report);
    ASSERT_EQ(west.buildings.size(), 1u);
    EXPECT_EQ(west.buildings[0].osm.id, 1);
    ASSERT_EQ(west.roads.size(), 1u);
    EXPECT_EQ(west.roads[0].osm.id, 10);
    EXPECT_EQ(west.roads[0].to_joint, 0);
    ASSERT_EQ(west.joints.size(), 1u);  // with its first edge
    EXPECT_EQ(west.joints[0].edges, std::vector<uint32_t>{0});  // road 11 went east
    ASSERT_EQ(west.sidewalks.size(), 1u);  // the corner, with its joint
    EXPECT_EQ(west.sidewalks[0].joint, 0);
    EXPECT_EQ(west.sidewalks[0].road, -1);
    EXPECT_EQ(west.lamps.size(), 1u);
    EXPECT_TRUE(west.trees.empty() && west.crossings.empty() && west.land_cover.empty());

    ASSERT_EQ(east.roads.size(), 1u);
    EXPECT_EQ(east.roads[0].osm.id, 11);
    EXPECT_EQ(east.roads[0].from_joint, -1);  // its joint is the west's: the merge links it again
    EXPECT_TRUE(east.joints.empty());
    ASSERT_EQ(east.sidewalks.size(), 1u);
    EXPECT_EQ(east.sidewalks[0].road, 0);
    ASSERT_EQ(east.crossings.size(), 1u);
    EXPECT_EQ(east.crossings[0].road, 0);
    EXPECT_EQ(east.trees.size(), 1u);
    EXPECT_EQ(east.land_cover.size(), 1u);
    EXPECT_EQ(report.dropped_count(ReportKind::TileBuildings, ReportReason::AnchorInAnotherTile), 2);
    EXPECT_EQ(report.kept_count(ReportKind::TileRoadEdges), 2);
}

// A wall goes with the middle of its ends (edge_anchor), as a path does: wall 21 reaches into the
// east tile but its anchor is west.
TEST(KeepInsideBox, RetainingWallsGoWithTheirLinesAnchor) {
    auto wall = [](int64_t way, std::vector<Vec2> line) {
        RetainingWall w;
        w.osm = {OsmType::Way, way};
        w.line = std::move(line);
        return w;
    };
    Scene west;
    west.retaining_walls = {wall(20, {{10, 0}, {20, 0}}), wall(21, {{-40, 5}, {0, 5}, {20, 5}}),
                            wall(22, {{-10, 9}, {-5, 9}})};
    Scene east = west;
    ParseReport report;
    keep_inside_box(west, kProjection, kWest, report);
    keep_inside_box(east, kProjection, kEast, report);
    ASSERT_EQ(west.retaining_walls.size(), 2u);
    EXPECT_EQ(west.retaining_walls[0].osm.id, 21);
    EXPECT_EQ(west.retaining_walls[0].line.size(), 3u);
    EXPECT_EQ(west.retaining_walls[1].osm.id, 22);
    ASSERT_EQ(east.retaining_walls.size(), 1u);
    EXPECT_EQ(east.retaining_walls[0].osm.id, 20);
    EXPECT_EQ(report.kept_count(ReportKind::TileRetainingWalls), 3);
    EXPECT_EQ(report.dropped_count(ReportKind::TileRetainingWalls, ReportReason::AnchorInAnotherTile), 3);
}

// A point exactly on the corner of four boxes belongs to one of them: the half-open edges.
TEST(KeepInsideBox, AnAnchorOnTheEdgeBelongsToOneTile) {
    const LatLonBox boxes[4] = {{{-90, -180}, {50, 8}}, {{-90, 8}, {50, 180}}, {{50, -180}, {90, 8}},
                                {{50, 8}, {90, 180}}};
    for (const LatLon corner : {LatLon{50, 8}, LatLon{50, 8.0000001}, LatLon{49.9999999, 8}}) {
        const Vec2 p = kProjection.to_local(corner.lat, corner.lon);
        int holders = 0;
        for (const LatLonBox& box : boxes) {
            Scene s;
            Tree t;
            t.position = p;
            s.trees = {t};
            ParseReport report;
            keep_inside_box(s, kProjection, box, report);
            holders += static_cast<int>(s.trees.size());
        }
        EXPECT_EQ(holders, 1) << corner.lat << "," << corner.lon;
    }
}

// The sea is made per tile within its core (tile_sea_box): every tile keeps its own, wherever
// its centroid.
TEST(KeepInsideBox, EveryTileKeepsItsSea) {
    for (const LatLonBox& box : {LatLonBox{{-90, -180}, {50, 8}}, LatLonBox{{50, 8}, {90, 180}}}) {
        Scene s;
        LandCover sea, water;
        sea.cover = LandCoverClass::Sea;
        water.cover = LandCoverClass::Water;
        sea.outer = water.outer = {{5000, 5000}, {6000, 5000}, {6000, 6000}};  // north-east of the origin
        s.land_cover = {sea, water};
        ParseReport report;
        keep_inside_box(s, kProjection, box, report);
        ASSERT_FALSE(s.land_cover.empty());
        EXPECT_EQ(s.land_cover[0].cover, LandCoverClass::Sea);
        EXPECT_EQ(s.land_cover.size(), box.min.lat == 50 ? 2u : 1u) << "other water goes by its anchor";
    }
}

// Four tiles' sea boxes cover the region's extract, each only a little beyond its core, and none
// beyond the extract's box.
TEST(TileSeaBox, TheTilesCoverTheExtractAndLittleMore) {
    const LatLon lo{49.8, 7.7}, hi{50.2, 8.3};  // the extract: about 43 x 44 km
    OsmData osm;
    osm.has_extract_bounds = true;
    osm.extract_min = lo;
    osm.extract_max = hi;
    const LatLonBox cores[4] = {{{-90, -180}, {50, 8}}, {{-90, 8}, {50, 180}}, {{50, -180}, {90, 8}}, {{50, 8}, {90, 180}}};
    Box2 boxes[4];
    for (int i = 0; i < 4; ++i) boxes[i] = tile_sea_box(cores[i], osm, kProjection);
    const Box2 whole = extract_box(osm, kProjection);
    for (const Box2& b : boxes) {
        EXPECT_GE(b.min.x, whole.min.x);
        EXPECT_GE(b.min.y, whole.min.y);
        EXPECT_LE(b.max.x, whole.max.x);
        EXPECT_LE(b.max.y, whole.max.y);
    }
    // Points of the extract, on a lattice of degrees: each one within one parse's sea box (where
    // the extract's curved edges do not bulge beyond it) is in a tile's.
    int points = 0;
    for (double lat = lo.lat; lat <= hi.lat; lat += 0.01)
        for (double lon = lo.lon; lon <= hi.lon; lon += 0.01) {
            const Vec2 p = kProjection.to_local(lat, lon);
            if (p.x < whole.min.x || p.x > whole.max.x || p.y < whole.min.y || p.y > whole.max.y) continue;
            ++points;
            bool covered = false;
            for (const Box2& b : boxes) covered = covered || (p.x >= b.min.x && p.x <= b.max.x && p.y >= b.min.y && p.y <= b.max.y);
            EXPECT_TRUE(covered) << lat << "," << lon;
        }
    EXPECT_GT(points, 2000);
    // The south-west tile's box ends near the origin (the cut), not at the extract's far edge:
    // within the bend of a meridian over 22 km at 50 N (about 0.2 degrees, 80 m) and the metre.
    EXPECT_NEAR(boxes[0].max.x, 0, 100);
    EXPECT_NEAR(boxes[0].max.y, 0, 100);
    EXPECT_LT(boxes[0].min.x, -21000);
    EXPECT_TRUE(tile_sea_box({{60, 8}, {90, 180}}, osm, kProjection).empty()) << "a core beyond the extract";
}

TEST(KeepInsideBox, ReturnsTheMapBuildingsKept) {
    Scene s = two_sided_scene();
    ParseReport report;
    EXPECT_EQ(keep_inside_box(s, kProjection, kEast, report, 1), 0u);  // building 1 of the first 1 went west
}

TEST(RingAnchor, IsTheAreaCentroid) {
    const Ring l = {{0, 0}, {10, 0}, {10, 2}, {2, 2}, {2, 10}, {0, 10}};  // an L
    const Vec2 c = ring_anchor(l);
    EXPECT_NEAR(c.x, 116.0 / 36, 1e-9);  // 10x2 at (5, 1) and 2x8 at (1, 6)
    EXPECT_NEAR(c.y, 116.0 / 36, 1e-9);
    const Vec2 d = ring_anchor({{0, 0}, {4, 0}, {8, 0}});  // degenerate: the box centre
    EXPECT_DOUBLE_EQ(d.x, 4);
    EXPECT_DOUBLE_EQ(d.y, 0);
}

TEST(LatLonText, ParsesAndRefuses) {
    const LatLon p = parse_lat_lon("49.44,7.76", "--origin");
    EXPECT_DOUBLE_EQ(p.lat, 49.44);
    EXPECT_DOUBLE_EQ(p.lon, 7.76);
    EXPECT_EQ(to_text(p), "49.44,7.76");
    const LatLonBox b = parse_lat_lon_box("-90,-180,52.5,13.4", "--keep-inside");
    EXPECT_EQ(to_text(b), "-90,-180,52.5,13.4");
    for (const char* bad : {"", "49", "49,", "49,7,1", "49;7", "x,7", "91,7", "49,181", "nan,7", "1e999,7"})
        EXPECT_THROW(parse_lat_lon(bad, "--origin"), Error) << bad;
    for (const char* bad : {"1,1,1,2", "2,1,1,2", "1,2,2,1", "1,1,2", "-91,0,0,1"})
        EXPECT_THROW(parse_lat_lon_box(bad, "--keep-inside"), Error) << bad;
    try {
        parse_lat_lon("91,7", "--origin");
    } catch (const Error& e) {
        EXPECT_STREQ(e.what(), "--origin: latitude 91 is outside -90..90");
    }
}

}  // namespace
