// --geojson: every road piece, joint, sidewalk, lamp and building as a feature in WGS84,
// coordinates that map back onto the scene, written atomically by the CLI.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>

#include "osmparse/core/projection.h"
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
