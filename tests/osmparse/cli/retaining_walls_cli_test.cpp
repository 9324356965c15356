// barrier=retaining_wall on the command line: with --dem the wall is in the scene, counted in the
// report and --info, the field steps at it and the GeoJSON has its top; without --dem the scene
// is byte for byte what it is without the wall in the map.
#include <gtest/gtest.h>

#include <filesystem>

#include "common/scene_io.h"
#include "tests/test_support.h"

using namespace citygen;
using namespace citygen::test;

namespace {

// A town around 49.50 N, 8.50 E: one building, a road, and (with_wall) a 3 m stone retaining
// wall 100 m north of the road, 145 m long, eastwards: the ground is lower on its south.
std::string town(bool with_wall) {
    std::string osm = R"(<?xml version="1.0" encoding="UTF-8"?>
<osm version="0.6">
  <node id="1" lat="49.5000" lon="8.5000"/>
  <node id="2" lat="49.5000" lon="8.5003"/>
  <node id="3" lat="49.5002" lon="8.5003"/>
  <node id="4" lat="49.5002" lon="8.5000"/>
  <node id="5" lat="49.4990" lon="8.4980"/>
  <node id="6" lat="49.4990" lon="8.5030"/>
)";
    if (with_wall)
        osm += R"(  <node id="7" lat="49.4999" lon="8.4990"/>
  <node id="8" lat="49.4999" lon="8.5000"/>
  <node id="9" lat="49.4999" lon="8.5010"/>
)";
    osm += R"(  <way id="10"><nd ref="1"/><nd ref="2"/><nd ref="3"/><nd ref="4"/><nd ref="1"/><tag k="building" v="yes"/></way>
  <way id="11"><nd ref="5"/><nd ref="6"/><tag k="highway" v="residential"/></way>
)";
    if (with_wall)
        osm += R"(  <way id="12"><nd ref="7"/><nd ref="8"/><nd ref="9"/><tag k="barrier" v="retaining_wall"/><tag k="height" v="3"/><tag k="material" v="stone"/></way>
)";
    return osm + "</osm>\n";
}

// SRTM3 samples 3 arc-seconds apart, rows north to south: a gentle slope up to the north and east.
std::string srtm3_tile() {
    std::string bytes;
    for (int row = 0; row < 1201; ++row)
        for (int col = 0; col < 1201; ++col) {
            const auto v = static_cast<uint16_t>(static_cast<int16_t>(100 + (1200 - row) + col));
            bytes.push_back(static_cast<char>(v >> 8));
            bytes.push_back(static_cast<char>(v & 0xff));
        }
    return bytes;
}

CommandResult parse(const std::string& osm, const std::string& args) {
    return run_command(quoted(osmparse_binary()) + " " + quoted(osm) + " " + args);
}

}  // namespace

TEST(RetainingWallsCli, WithADemTheWallIsInTheSceneAndTheGroundStepsAtIt) {
    TempDir dir;
    write_text(dir.file("town.osm"), town(true));
    write_text(dir.file("N49E008.hgt"), srtm3_tile());
    const std::string scene = dir.file("town.scene");
    const CommandResult r = parse(dir.file("town.osm"), "--dem " + quoted(dir.file("N49E008.hgt")) + " -o " +
                                                            quoted(scene) + " --geojson " + quoted(dir.file("town.geojson")));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("retaining walls"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("on a retaining wall's low side, lowered"), std::string::npos) << r.err;
    const Scene s = load_scene(scene);
    ASSERT_EQ(s.retaining_walls.size(), 1u);
    EXPECT_EQ(s.retaining_walls[0].osm, (OsmRef{OsmType::Way, 12}));
    EXPECT_EQ(s.retaining_walls[0].line.size(), 3u);
    EXPECT_DOUBLE_EQ(s.retaining_walls[0].height, 3);
    EXPECT_EQ(s.retaining_walls[0].material, WallMaterial::Stone);
    const CommandResult info = run_command(quoted(osmparse_binary()) + " --info " + quoted(scene));
    EXPECT_NE(info.out.find("retaining_walls: 1 (1 with a tagged height), 145 m long"), std::string::npos) << info.out;
    const std::string geojson = read_text(dir.file("town.geojson"));
    EXPECT_NE(geojson.find("\"type\":\"LineString\""), std::string::npos);
    EXPECT_NE(geojson.find("\"kind\":\"retaining_wall\",\"osm\":\"w12\",\"height\":3.000"), std::string::npos);
}

TEST(RetainingWallsCli, WithoutADemTheSceneIsWhatItIsWithoutTheWall) {
    TempDir with, without;
    write_text(with.file("town.osm"), town(true));
    write_text(without.file("town.osm"), town(false));
    ASSERT_EQ(parse(with.file("town.osm"), "-q -o " + quoted(with.file("town.scene"))).exit_code, 0);
    ASSERT_EQ(parse(without.file("town.osm"), "-q -o " + quoted(without.file("town.scene"))).exit_code, 0);
    const std::string bytes = read_text(with.file("town.scene"));
    EXPECT_FALSE(bytes.empty());
    EXPECT_EQ(bytes, read_text(without.file("town.scene")));
    const CommandResult r = parse(with.file("town.osm"), "-o " + quoted(with.file("again.scene")));
    EXPECT_EQ(r.err.find("retaining walls"), std::string::npos) << "no report row without a field: " << r.err;
}
