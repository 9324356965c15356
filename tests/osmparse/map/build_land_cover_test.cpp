// Land cover and the sea: hand-made fixtures (tests/data/map_*.osm, see make_map_fixtures.py)
// with the sea on the right side of the coastline, islands and lakes as holes, broken data
// counted; and on Monaco, the sea where the sea is and valid polygons everywhere.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "common/scene_io.h"
#include "osmparse/map/assemble_sea.h"
#include "osmparse/map/build_land_cover.h"
#include "osmparse/pipeline.h"
#include "osmparse/polygons/clean_footprint.h"
#include "osmparse/polygons/ring_is_simple.h"
#include "osmparse/read/land_cover_tags.h"
#include "tests/osmparse/parse_quietly.h"

using namespace citygen;
using citygen::test::parse_quietly;

namespace {

Scene fixture(const std::string& name, ParseReport& report) {
    return parse_quietly(std::string(CITYGEN_SOURCE_DIR) + "/tests/data/map_" + name + ".osm", report);
}

// Inside the polygon (outer minus holes) of some land cover of class c.
bool covered(const Scene& s, LandCoverClass c, Vec2 p) {
    for (const LandCover& x : s.land_cover) {
        if (x.cover != c || !point_in_ring(p, x.outer)) continue;
        bool in_hole = false;
        for (const Ring& h : x.holes) in_hole = in_hole || point_in_ring(p, h);
        if (!in_hole) return true;
    }
    return false;
}

size_t count(const Scene& s, LandCoverClass c) {
    size_t n = 0;
    for (const LandCover& x : s.land_cover) n += x.cover == c;
    return n;
}

void expect_valid(const Scene& s) {
    for (const LandCover& x : s.land_cover) {
        EXPECT_TRUE(ring_is_simple(x.outer)) << to_string(x.osm);
        EXPECT_GT(signed_area(x.outer), 0) << to_string(x.osm);
        for (const Ring& h : x.holes) {
            EXPECT_TRUE(ring_is_simple(h)) << to_string(x.osm);
            EXPECT_LT(signed_area(h), 0) << to_string(x.osm);
            EXPECT_TRUE(point_in_ring(interior_point(h), x.outer)) << to_string(x.osm);
        }
    }
}


// A point of the fixture's local metres (make_map_fixtures.py: around 43.7N 7.4E) in the
// scene's coordinates (whose origin is the centre of the data).
Vec2 at(const Scene& s, double x, double y) {
    const Projection projection(s.header.origin_lat, s.header.origin_lon);
    const double m_lat = 111320.0, m_lon = 111320.0 * std::cos(43.7 * kPi / 180);
    return projection.to_local(43.7 + y / m_lat, 7.4 + x / m_lon);
}

}  // namespace

TEST(Sea, CoastlineAcrossTheExtractPutsTheSeaOnItsRight) {
    ParseReport report;
    const Scene s = fixture("coast_cut", report);
    ASSERT_EQ(count(s, LandCoverClass::Sea), 1u);
    EXPECT_TRUE(covered(s, LandCoverClass::Sea, at(s, 0, -150)));
    EXPECT_TRUE(covered(s, LandCoverClass::Sea, at(s, -190, -190)));
    EXPECT_FALSE(covered(s, LandCoverClass::Sea, at(s, 0, 150)));
    EXPECT_FALSE(covered(s, LandCoverClass::Sea, at(s, 0, 100)));  // the house
    expect_valid(s);
}

TEST(Sea, TheSameCoastlineDrawnTheOtherWayRoundFloodsTheOtherSide) {
    ParseReport report;
    const Scene s = fixture("coast_cut_reversed", report);
    ASSERT_EQ(count(s, LandCoverClass::Sea), 1u);
    EXPECT_TRUE(covered(s, LandCoverClass::Sea, at(s, 0, 150)));
    EXPECT_FALSE(covered(s, LandCoverClass::Sea, at(s, 0, -150)));
    EXPECT_FALSE(covered(s, LandCoverClass::Sea, at(s, 0, -100)));
    expect_valid(s);
}

TEST(Sea, ACoastlineCuttingACornerClosesAlongTheEdgeAroundTheOtherCorners) {
    ParseReport report;
    const Scene s = fixture("coast_corner", report);
    ASSERT_EQ(count(s, LandCoverClass::Sea), 1u);
    EXPECT_FALSE(covered(s, LandCoverClass::Sea, at(s, -190, -190)));  // the land corner
    for (Vec2 p : {Vec2{190, -190}, Vec2{190, 190}, Vec2{-190, 190}, Vec2{0, 0}})
        EXPECT_TRUE(covered(s, LandCoverClass::Sea, at(s, p.x, p.y))) << p.x << "," << p.y;
    expect_valid(s);
}

TEST(Sea, AnIslandIsAHoleInASeaFillingTheExtract) {
    ParseReport report;
    const Scene s = fixture("island", report);
    ASSERT_EQ(count(s, LandCoverClass::Sea), 1u);
    EXPECT_EQ(s.land_cover[0].holes.size(), 1u);
    EXPECT_FALSE(covered(s, LandCoverClass::Sea, at(s, 0, 0)));
    EXPECT_TRUE(covered(s, LandCoverClass::Sea, at(s, -190, -190)));
    EXPECT_TRUE(covered(s, LandCoverClass::Sea, at(s, 150, 150)));
    expect_valid(s);
}

TEST(Sea, ACoastlineCutByAClippedExtractIsCarriedToTheEdge) {
    ParseReport report;
    const Scene s = fixture("coast_clipped", report);
    ASSERT_EQ(count(s, LandCoverClass::Sea), 1u);
    EXPECT_TRUE(covered(s, LandCoverClass::Sea, at(s, 0, -150)));
    EXPECT_TRUE(covered(s, LandCoverClass::Sea, at(s, -195, -50)));  // beside the carried west end
    EXPECT_FALSE(covered(s, LandCoverClass::Sea, at(s, 0, 150)));
    EXPECT_FALSE(covered(s, LandCoverClass::Sea, at(s, 0, 100)));
    EXPECT_EQ(report.note_count(ReportKind::CoastlineWays, ReportReason::CutByExtract), 2);
    expect_valid(s);
}

TEST(Sea, ACoastlineEndingInsideTheExtractGivesNoSeaAndIsCounted) {
    ParseReport report;
    const Scene s = fixture("coast_broken", report);
    EXPECT_EQ(count(s, LandCoverClass::Sea), 0u);
    EXPECT_EQ(report.dropped_count(ReportKind::SeaPolygons, ReportReason::CoastlineEndsInside),
              1);
}

TEST(Sea, CoastlinesDisagreeingInDirectionGiveNoSea) {
    // Two parallel coastlines both with the land on the north: they cannot both be right.
    Box2 box;
    box.extend({-100, -100});
    box.extend({100, 100});
    ParseReport report;
    const std::vector<CoastlineChain> chains{{{{-200, -50}, {200, -50}}, 1}, {{{-200, 50}, {200, 50}}, 2}};
    EXPECT_TRUE(sea_from_chains(chains, box, report).empty());
    EXPECT_EQ(report.dropped_count(ReportKind::SeaPolygons, ReportReason::CoastlineDirectionsDisagree),
              1);
}

TEST(Sea, ASeaHoldingMostBuildingsIsTakenForLandAndDropped) {
    // A coastline with the land south, and twelve houses south of it... but the ways are
    // reversed, so the "sea" lies where the houses stand: dropped, never a flooded city.
    const Projection projection(43.7, 7.4);
    OsmData osm;
    OsmWay way;
    way.id = 5;
    for (double x : {-300.0, 0.0, 300.0}) {
        double lat, lon;
        projection.to_wgs84({x, 0}, lat, lon);
        way.nodes.push_back(static_cast<int64_t>(x + 1000));
        way.locations.push_back({lat, lon});
    }
    osm.coastlines.push_back(way);  // west -> east: sea in the south
    std::vector<Building> houses;
    for (int k = 0; k < 12; ++k) {
        Building b;
        const double x = -150 + 25 * k, y = -100;
        b.outer = {{x, y}, {x + 8, y}, {x + 8, y + 8}, {x, y + 8}};
        houses.push_back(b);
    }
    Box2 box;
    box.extend({-200, -200});
    box.extend({200, 200});
    ParseReport report;
    EXPECT_TRUE(assemble_sea(osm, projection, box, houses, report).empty());
    EXPECT_EQ(report.dropped_count(ReportKind::SeaPolygons, ReportReason::WouldFloodCity), 1);
}

TEST(LandCover, ALakeMultipolygonKeepsItsIslandAsAHole) {
    ParseReport report;
    const Scene s = fixture("lake_island", report);
    ASSERT_EQ(count(s, LandCoverClass::Water), 1u);
    EXPECT_EQ(s.land_cover[0].osm, (OsmRef{OsmType::Relation, 100}));
    EXPECT_EQ(s.land_cover[0].holes.size(), 1u);
    EXPECT_TRUE(covered(s, LandCoverClass::Water, at(s, -80, 0)));
    EXPECT_FALSE(covered(s, LandCoverClass::Water, at(s, 10, 0)));
    expect_valid(s);
}

TEST(LandCover, AParkWithAPondASquareAndBuiltUpGroundEachGetTheirClass) {
    ParseReport report;
    const Scene s = fixture("park_pond", report);
    EXPECT_EQ(count(s, LandCoverClass::Green), 1u);
    EXPECT_EQ(count(s, LandCoverClass::Water), 1u);
    EXPECT_EQ(count(s, LandCoverClass::Paved), 1u);
    EXPECT_EQ(count(s, LandCoverClass::BuiltUp), 1u);
    // The pond lies on the park, the park and the square on the residential ground.
    EXPECT_GT(land_cover_priority(LandCoverClass::Water), land_cover_priority(LandCoverClass::Green));
    EXPECT_GT(land_cover_priority(LandCoverClass::Green), land_cover_priority(LandCoverClass::BuiltUp));
    EXPECT_GT(land_cover_priority(LandCoverClass::Paved), land_cover_priority(LandCoverClass::BuiltUp));
    expect_valid(s);
}

TEST(LandCover, ARiverbankWithAMissingMemberIsSkippedAndCounted) {
    ParseReport report;
    const Scene s = fixture("riverbank_missing_member", report);
    EXPECT_TRUE(s.land_cover.empty());
    EXPECT_EQ(report.dropped_count(ReportKind::LandCoverAreas, ReportReason::RelationMembersMissing), 1);
}

TEST(LandCover, ClassesFollowTheTable) {
    auto cls = [](std::vector<std::pair<std::string, std::string>> tags) {
        OsmTags t;
        t.entries = std::move(tags);
        return land_cover_class(t);
    };
    EXPECT_EQ(cls({{"natural", "water"}}), LandCoverClass::Water);
    EXPECT_EQ(cls({{"waterway", "riverbank"}}), LandCoverClass::Water);
    EXPECT_EQ(cls({{"landuse", "reservoir"}}), LandCoverClass::Water);
    EXPECT_EQ(cls({{"leisure", "park"}}), LandCoverClass::Green);
    EXPECT_EQ(cls({{"landuse", "cemetery"}}), LandCoverClass::Green);
    EXPECT_EQ(cls({{"natural", "wood"}}), LandCoverClass::Forest);
    EXPECT_EQ(cls({{"landuse", "forest"}}), LandCoverClass::Forest);
    EXPECT_EQ(cls({{"highway", "pedestrian"}, {"area", "yes"}}), LandCoverClass::Paved);
    EXPECT_EQ(cls({{"highway", "pedestrian"}}), std::nullopt);  // a street, not an area
    EXPECT_EQ(cls({{"amenity", "parking"}}), LandCoverClass::Paved);
    EXPECT_EQ(cls({{"natural", "beach"}}), LandCoverClass::Sand);
    EXPECT_EQ(cls({{"landuse", "farmland"}}), LandCoverClass::Farmland);
    EXPECT_EQ(cls({{"landuse", "retail"}}), LandCoverClass::BuiltUp);
    EXPECT_EQ(cls({{"natural", "coastline"}}), std::nullopt);
    EXPECT_EQ(cls({{"amenity", "bench"}}), std::nullopt);
    EXPECT_EQ(cls({{"man_made", "pier"}}), LandCoverClass::Paved);
    EXPECT_EQ(cls({{"man_made", "breakwater"}}), LandCoverClass::Paved);
    EXPECT_EQ(cls({{"man_made", "tower"}}), std::nullopt);
}

TEST(LandCover, PiersAreKeptOnlyOnAHeightField) {
    OsmData osm;
    OsmArea pier;
    pier.ref = {OsmType::Way, 7};
    pier.tags.entries = {{"man_made", "pier"}, {"area", "yes"}};
    pier.polygons.push_back({{{43.7, 7.4}, {43.7, 7.4005}, {43.7002, 7.4005}, {43.7002, 7.4}, {43.7, 7.4}}, {}});
    osm.land_cover_areas.push_back(pier);
    const Projection projection(43.7, 7.4);
    ParseReport report;
    EXPECT_TRUE(build_land_cover(osm, projection, BuildingParams{}, false, report).empty());
    const std::vector<LandCover> kept = build_land_cover(osm, projection, BuildingParams{}, true, report);
    ASSERT_EQ(kept.size(), 1u);
    EXPECT_EQ(kept[0].cover, LandCoverClass::Paved);
}

TEST(LandCover, APierMappedAsALineIsAPavedStripAlongItOnlyOnAHeightField) {
    OsmData osm;
    OsmWay jetty;  // about 80 m east, then 40 m north; width untagged
    jetty.id = 9;
    jetty.locations = {{43.7, 7.4}, {43.7, 7.401}, {43.70036, 7.401}};
    osm.pier_lines.push_back(jetty);
    OsmWay wide = jetty;  // a breakwater 8 m wide, about 200 m south
    wide.id = 10;
    wide.tags.entries = {{"width", "8"}};
    for (LatLon& l : wide.locations) l.lat -= 0.0018;
    osm.pier_lines.push_back(wide);
    const Projection projection(43.7, 7.4);
    ParseReport report;
    EXPECT_TRUE(build_land_cover(osm, projection, BuildingParams{}, false, report).empty());
    const std::vector<LandCover> kept = build_land_cover(osm, projection, BuildingParams{}, true, report);
    ASSERT_EQ(kept.size(), 4u) << "a strip per segment";
    Scene s;
    s.land_cover = kept;
    for (const LandCover& c : kept) EXPECT_EQ(c.cover, LandCoverClass::Paved);
    const Vec2 a = projection.to_local(43.7, 7.4), b = projection.to_local(43.7, 7.401);
    const Vec2 c = projection.to_local(43.70036, 7.401);
    const Vec2 across = perp_left(normalize(b - a)), up = normalize(c - b);
    // Along the jetty within 1.5 m of it, around its bend, near its end; not 2 m off it.
    for (Vec2 p : {(a + b) * 0.5 + across * 1.4, b + normalize(b - a) * 1.4 - up * 1.4, c - up * 1.0})
        EXPECT_TRUE(covered(s, LandCoverClass::Paved, p)) << p.x << " " << p.y;
    EXPECT_FALSE(covered(s, LandCoverClass::Paved, (a + b) * 0.5 + across * 2.0));
    const Vec2 south = projection.to_local(43.6982, 7.4005);
    EXPECT_TRUE(covered(s, LandCoverClass::Paved, south + across * 3.9)) << "its width tag";
    EXPECT_EQ(report.note_count(ReportKind::LandCoverPaved, ReportReason::PierLineWidthDefault), 1);
}

TEST(LandCover, EveryClassHasItsReportRow) {
    for (int i = 0; i < kLandCoverClassCount; ++i) {
        const LandCoverClass c = static_cast<LandCoverClass>(i);
        EXPECT_EQ(std::string(text_of(land_cover_row(c))), std::string("land cover: ") + to_string(c));
    }
}

TEST(LandCover, MonacoHasTheSeaInTheSouthEastAndValidPolygons) {
    const std::string path = std::string(CITYGEN_SHARED_DATA_DIR) + "/monaco.osm.pbf";
    if (!std::filesystem::exists(path)) GTEST_SKIP() << "no Monaco extract";
    ParseReport report;
    const Scene s = parse_quietly(path, report);
    const Projection projection(s.header.origin_lat, s.header.origin_lon);
    ASSERT_GE(count(s, LandCoverClass::Sea), 1u);
    // Open sea off Monaco, the harbour basin; the casino, the palace and the stadium on land.
    EXPECT_TRUE(covered(s, LandCoverClass::Sea, projection.to_local(43.7280, 7.4400)));
    EXPECT_TRUE(covered(s, LandCoverClass::Sea, projection.to_local(43.7345, 7.4250)));
    EXPECT_FALSE(covered(s, LandCoverClass::Sea, projection.to_local(43.7396, 7.4281)));
    EXPECT_FALSE(covered(s, LandCoverClass::Sea, projection.to_local(43.7314, 7.4198)));
    EXPECT_FALSE(covered(s, LandCoverClass::Sea, projection.to_local(43.7276, 7.4155)));
    EXPECT_GE(count(s, LandCoverClass::Green), 10u);
    EXPECT_GE(count(s, LandCoverClass::Water), 5u);
    expect_valid(s);
    // No building stands in the sea (piers are land in OSM's coastline); the one exception is
    // a building mapped on the water side of Monaco's coastline.
    size_t wet = 0;
    for (const Building& b : s.buildings) wet += covered(s, LandCoverClass::Sea, interior_point(b.outer));
    EXPECT_LE(wet, 1u);
}
