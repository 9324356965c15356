// --geojson: every road piece, joint, sidewalk, lamp and building as a feature in WGS84,
// coordinates that map back onto the scene, written atomically by the CLI.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "common/projection.h"
#include "common/stairs.h"
#include "osmparse/output/write_geojson.h"
#include "osmparse/pipeline.h"
#include "tests/osmparse/parse_quietly.h"
#include "tests/test_support.h"

using namespace citygen;
using namespace citygen::test;

namespace {

size_t count(const std::string& text, const std::string& what) {
    size_t n = 0;
    for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
    return n;
}

Scene parse(const std::string& fixture) {
    ParseReport report;
    return parse_quietly(source_path("tests/data/" + fixture), report);
}

}  // namespace

TEST(RoadGeoJson, OneFeaturePerObjectWithItsProperties) {
    const Scene s = parse("road_brushing_building.osm");
    const std::string text = scene_to_geojson(s);
    EXPECT_EQ(count(text, "\"type\":\"Feature\""),
              s.buildings.size() + s.roads.size() + s.joints.size() + s.sidewalks.size() + s.lamps.size());
    EXPECT_EQ(count(text, "\"kind\":\"road\""), s.roads.size());
    EXPECT_EQ(count(text, "\"kind\":\"building\""), s.buildings.size());
    EXPECT_EQ(count(text, "\"kind\":\"lamp\""), s.lamps.size());
    EXPECT_EQ(count(text, "\"source\":\"generated\""), s.lamps.size());
    EXPECT_EQ(count(text, "\"osm\":\"w10\""), s.roads.size() + s.sidewalks.size() + s.lamps.size());
    EXPECT_NE(text.find("\"height\":10.000"), std::string::npos) << "the building's tagged height";
}

TEST(RoadGeoJson, CoordinatesMapBackOntoTheScene) {
    const Scene s = parse("road_cross.osm");
    const std::string text = scene_to_geojson(s);
    const size_t road = text.find("\"kind\":\"road\"");
    ASSERT_NE(road, std::string::npos);
    const size_t feature = text.rfind("{\"type\":\"Feature\"", road);
    const size_t coords = text.find("[[[", feature);
    double lon = 0, lat = 0;
    ASSERT_EQ(std::sscanf(text.c_str() + coords, "[[[%lf,%lf]", &lon, &lat), 2);
    const Projection projection(s.header.origin_lat, s.header.origin_lon);
    const Vec2 back = projection.to_local(lat, lon);
    EXPECT_LT(length(back - s.roads[0].quad[0]), 0.01);
}

TEST(RoadGeoJson, CliWritesItAndFailsCleanlyOnABadPath) {
    TempDir dir;
    const std::string input = quoted(source_path("tests/data/road_t.osm"));
    CommandResult ok = run_command(quoted(osmparse_binary()) + " -q " + input + " -o " + quoted(dir.file("t.scene")) +
                                   " --geojson " + quoted(dir.file("t.geojson")));
    ASSERT_EQ(ok.exit_code, 0) << ok.err;
    const std::string text = read_text(dir.file("t.geojson"));
    EXPECT_EQ(text.rfind("{\"type\":\"FeatureCollection\"", 0), 0u);
    EXPECT_EQ(count(text, "\"kind\":\"joint\""), 1u);

    CommandResult bad = run_command(quoted(osmparse_binary()) + " -q " + input + " -o " + quoted(dir.file("u.scene")) +
                                    " --geojson " + quoted(dir.file("missing-dir/t.geojson")));
    EXPECT_NE(bad.exit_code, 0);
    EXPECT_EQ(count(bad.err, "\n"), 1u) << bad.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("missing-dir/t.geojson")));
}

namespace {

// A scene on a plane slope, ground = 2 + 0.1 x + 0.05 y above a reference of 100 m (the cell
// triangles of a plane are the plane), with one building, one road and one tree.
Scene sloping_scene() {
    Scene s;
    s.header.origin_lat = 43.73;
    s.header.origin_lon = 7.42;
    HeightField& f = s.terrain;
    f.origin = {-50, -50};
    f.cell = 10;
    f.nx = f.ny = 11;
    f.reference_altitude = 100;
    f.vertical_datum = "EGM96";
    for (uint32_t j = 0; j < f.ny; ++j)
        for (uint32_t i = 0; i < f.nx; ++i)
            f.heights.push_back(static_cast<float>(2 + 0.1 * (-50 + 10.0 * i) + 0.05 * (-50 + 10.0 * j)));
    Building b;
    b.outer = {{3, 4}, {13, 4}, {13, 12}, {3, 12}};
    b.height = 10;
    s.buildings.push_back(b);
    RoadEdge r;
    r.quad = {{-20.5, -7.25}, {20.5, -7.25}, {20.5, -3.75}, {-20.5, -3.75}};
    r.width = 3.5;
    s.roads.push_back(r);
    Tree t;
    t.position = {-12, 31};
    s.trees.push_back(t);
    return s;
}

double plane(Vec2 p) { return 100 + 2 + 0.1 * p.x + 0.05 * p.y; }

// Every [lon,lat,z] of the feature of `kind`, mapped back to scene coordinates.
std::vector<Vec3> feature_points(const std::string& text, const Scene& s, const std::string& kind) {
    const size_t at = text.find("\"kind\":\"" + kind + "\"");
    const size_t begin = text.rfind("\"coordinates\":", at), end = text.find("]}", begin);
    const Projection projection(s.header.origin_lat, s.header.origin_lon);
    std::vector<Vec3> points;
    for (size_t k = text.find_first_of("-0123456789", begin); k < end;) {
        double lon = 0, lat = 0, z = 0;
        int used = 0;
        if (std::sscanf(text.c_str() + k, "%lf,%lf,%lf%n", &lon, &lat, &z, &used) != 3) break;
        const Vec2 p = projection.to_local(lat, lon);
        points.push_back({p.x, p.y, z});
        k = text.find_first_of("-0123456789", k + used);
    }
    return points;
}

}  // namespace

TEST(TerrainGeoJson, BuildingsAtTheirLowestCornerRoadsAndTreesOnTheGround) {
    const Scene s = sloping_scene();
    const std::string text = scene_to_geojson(s);
    const std::vector<Vec3> building = feature_points(text, s, "building");
    ASSERT_EQ(building.size(), 5u);  // the ring repeats its first point
    for (const Vec3& p : building) EXPECT_NEAR(p.z, plane({3, 4}), 1e-3) << "every vertex at the lowest corner";
    const std::vector<Vec3> road = feature_points(text, s, "road");
    ASSERT_EQ(road.size(), 5u);
    for (const Vec3& p : road) EXPECT_NEAR(p.z, plane({p.x, p.y}), 2e-3) << p.x << "," << p.y;
    EXPECT_NEAR(road[1].z - road[0].z, 0.1 * 41, 2e-3) << "the slope along the road";
    const std::vector<Vec3> tree = feature_points(text, s, "tree");
    ASSERT_EQ(tree.size(), 1u);
    EXPECT_NEAR(tree[0].z, plane({-12, 31}), 1e-3);
}

TEST(TerrainGeoJson, WithoutAFieldCoordinatesStayTwoDimensional) {
    Scene s = sloping_scene();
    s.terrain = HeightField{};
    const std::string text = scene_to_geojson(s);
    EXPECT_TRUE(feature_points(text, s, "building").empty()) << "no third number";
    EXPECT_EQ(count(text, "]]]"), 2u);
    EXPECT_NE(text.find("[[[7.42"), std::string::npos);
    const std::string point = "\"type\":\"Point\",\"coordinates\":[";
    const size_t tree = text.find(point);
    ASSERT_NE(tree, std::string::npos);
    double lon = 0, lat = 0;
    char after = 0;
    ASSERT_EQ(std::sscanf(text.c_str() + tree + point.size(), "%lf,%lf%c", &lon, &lat, &after), 3);
    EXPECT_EQ(after, ']') << "two numbers";
}

// Steep steps are drawn by render as a stair (common/stairs.h): their polygon's vertices take the
// stair's line between its ends, within a riser of the tread drawn there, not the ground beside
// it. Here the ground also rises across the strip (0.5 per metre both ways), so the draped
// corners lie half a metre off the stair's line.
TEST(TerrainGeoJson, SteepStepsAtTheirStairsHeights) {
    Scene s = sloping_scene();
    HeightField& f = s.terrain;
    for (uint32_t j = 0; j < f.ny; ++j)
        for (uint32_t i = 0; i < f.nx; ++i)
            f.heights[j * f.nx + i] = static_cast<float>(0.5 * (-50 + 10.0 * i) + 0.5 * (-50 + 10.0 * j));
    s.buildings.clear();
    s.roads.clear();
    s.trees.clear();
    PathEdge p;
    p.path_class = PathClass::Steps;
    p.centreline = {{-10, 1}, {10, 1}};
    p.quad = {{-10, 0}, {10, 0}, {10, 2}, {-10, 2}};
    p.width = 2;
    s.paths = {p};
    StairPlan stair;
    ASSERT_TRUE(plan_stair(s, p, &stair));
    const std::vector<Vec3> points = feature_points(scene_to_geojson(s), s, "path");
    ASSERT_EQ(points.size(), 5u);
    for (const Vec3& q : points) {
        const double line = 100 + 0.5 * q.x + 0.5;  // the ground along the centreline, y = 1
        EXPECT_NEAR(q.z, line, 2e-3) << q.x << "," << q.y;
        // The tread over the vertex (the first or the last at these corners).
        const int k = q.x < 0 ? 0 : stair.steps - 1;
        const double tread = 100 + stair.z_low + (k + 1) * stair.rise();
        EXPECT_LE(q.z, tread + 2e-3);
        EXPECT_GE(q.z, tread - stair.rise() - 2e-3);
    }
    EXPECT_NEAR(points[2].z - points[1].z, 0, 2e-3) << "level across the strip, as the treads are";

    s.paths[0].path_class = PathClass::Footway;  // any other path stays draped
    for (const Vec3& q : feature_points(scene_to_geojson(s), s, "path"))
        EXPECT_NEAR(q.z, 100 + 0.5 * q.x + 0.5 * q.y, 2e-3) << q.x << "," << q.y;
}
