// osmparse --dem on the command line, with an SRTM3 tile written here (no GDAL needed: an .hgt is
// 1201 x 1201 big-endian int16 metres, its place in its name): the field in the scene and in
// both programs' --info, voids counted; bad DEMs and resolutions exit non-zero with one line and
// leave an existing output untouched.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "tests/test_support.h"

using namespace citygen::test;
namespace fs = std::filesystem;

namespace {

const std::string kPrevious = "previous contents, must survive a failed run\n";

// A town around 49.50 N, 8.50 E: one building and a road.
const char* kTown = R"(<?xml version="1.0" encoding="UTF-8"?>
<osm version="0.6">
  <node id="1" lat="49.5000" lon="8.5000"/>
  <node id="2" lat="49.5000" lon="8.5003"/>
  <node id="3" lat="49.5002" lon="8.5003"/>
  <node id="4" lat="49.5002" lon="8.5000"/>
  <node id="5" lat="49.4990" lon="8.4980"/>
  <node id="6" lat="49.4990" lon="8.5030"/>
  <way id="10"><nd ref="1"/><nd ref="2"/><nd ref="3"/><nd ref="4"/><nd ref="1"/><tag k="building" v="yes"/></way>
  <way id="11"><nd ref="5"/><nd ref="6"/><tag k="highway" v="residential"/></way>
</osm>
)";

// SRTM3 samples 3 arc-seconds apart, rows north to south: a slope rising 1 m per sample to the
// north and east from 100 m, with a 5 x 5 void (-32768) under the town.
std::string srtm3_tile() {
    std::string bytes;
    for (int row = 0; row < 1201; ++row)
        for (int col = 0; col < 1201; ++col) {
            int h = 100 + (1200 - row) + col;
            if (std::abs(row - 600) <= 2 && std::abs(col - 600) <= 2) h = -32768;  // 49.5 N, 8.5 E
            const auto v = static_cast<uint16_t>(static_cast<int16_t>(h));
            bytes.push_back(static_cast<char>(v >> 8));
            bytes.push_back(static_cast<char>(v & 0xff));
        }
    return bytes;
}

class TerrainCli : public testing::Test {
protected:
    void SetUp() override {
        write_text(dir_.file("town.osm"), kTown);
        write_text(dir_.file("N49E008.hgt"), srtm3_tile());
    }
    std::string parse(const std::string& args) const {
        return quoted(osmparse_binary()) + " " + quoted(dir_.file("town.osm")) + " " + args;
    }
    // Fails with one line naming `message_part`; out.scene keeps what it held and nothing is left beside it.
    void expect_failure(const std::string& args, const std::string& message_part) {
        write_text(dir_.file("out.scene"), kPrevious);
        size_t files = 0;
        for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_.path())) ++files;
        const CommandResult r = run_command(parse(args + " -o " + quoted(dir_.file("out.scene"))));
        EXPECT_NE(r.exit_code, 0) << args;
        EXPECT_EQ(count_lines(r.err), 1) << r.err;
        EXPECT_NE(r.err.find(message_part), std::string::npos) << r.err;
        EXPECT_EQ(read_text(dir_.file("out.scene")), kPrevious);
        size_t after = 0;
        for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_.path())) ++after;
        EXPECT_EQ(after, files) << "files left behind";
    }
    TempDir dir_;
};

}  // namespace

TEST_F(TerrainCli, TheFieldIsInTheSceneAndInBothPrograms) {
    const std::string scene = dir_.file("town.scene");
    const CommandResult r = run_command(parse("--dem " + quoted(dir_.file("N49E008.hgt")) + " -o " + quoted(scene)));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.err.find("terrain nodes"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("void, filled from its neighbours"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("names no vertical datum: EGM96 geoid assumed"), std::string::npos) << r.err;
    for (const CommandResult& info : {run_command(quoted(osmparse_binary()) + " --info " + quoted(scene)),
                                      render("--print-scene-info " + quoted(scene))}) {
        EXPECT_EQ(info.exit_code, 0) << info.err;
        EXPECT_NE(info.out.find("format_version: 1.2"), std::string::npos) << info.out;
        EXPECT_NE(info.out.find("terrain: ["), std::string::npos) << info.out;
        EXPECT_NE(info.out.find("nodes ("), std::string::npos) << info.out;
        // The slope climbs 1 m per 3 arc-seconds: the town sits at about 100 + 600 + 600 m.
        const size_t at = info.out.find("terrain_heights: ");
        ASSERT_NE(at, std::string::npos) << info.out;
        const double lowest = std::atof(info.out.c_str() + at + 17);
        EXPECT_GT(lowest, 1290);
        EXPECT_LT(lowest, 1300);
        EXPECT_NE(info.out.find("dem = N49E008.hgt"), std::string::npos) << info.out;
    }
}

TEST_F(TerrainCli, WithoutADemTheSceneIsFlat) {
    const std::string scene = dir_.file("flat.scene");
    ASSERT_EQ(run_command(parse("-q -o " + quoted(scene))).exit_code, 0);
    const CommandResult info = run_command(quoted(osmparse_binary()) + " --info " + quoted(scene));
    EXPECT_NE(info.out.find("terrain: none (flat)"), std::string::npos) << info.out;
    EXPECT_EQ(info.out.find("  dem = "), std::string::npos) << info.out;
}

TEST_F(TerrainCli, ADemOptionBeforeTheInputTakesOneFile) {
    const std::string scene = dir_.file("town.scene");
    const CommandResult r = run_command(quoted(osmparse_binary()) + " -q --dem " + quoted(dir_.file("N49E008.hgt")) +
                                        " " + quoted(dir_.file("town.osm")) + " -o " + quoted(scene));
    EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST_F(TerrainCli, ADemThatDoesNotOverlapTheExtract) {
    write_text(dir_.file("N10E010.hgt"), srtm3_tile());
    expect_failure("--dem " + quoted(dir_.file("N10E010.hgt")), "does not overlap the extract");
}

TEST_F(TerrainCli, TruncatedMissingAndCorruptDems) {
    write_text(dir_.file("N49E009.hgt"), srtm3_tile().substr(0, 1000000));
    expect_failure("--dem " + quoted(dir_.file("N49E009.hgt")), "N49E009.hgt: not a raster GDAL reads");
    expect_failure("--dem " + quoted(dir_.file("nowhere.hgt")), "nowhere.hgt: no such file");
    write_text(dir_.file("tile.hgt.zip"), "PK\x03\x04 not really a zip");
    expect_failure("--dem " + quoted(dir_.file("tile.hgt.zip")), "tile.hgt.zip: not a zip file");
    expect_failure("--dem " + quoted(dir_.path()), "not a regular file");
}

TEST_F(TerrainCli, AbsurdResolutions) {
    const std::string dem = "--dem " + quoted(dir_.file("N49E008.hgt"));
    for (const char* value : {"0", "-5", "nan", "inf"})
        expect_failure(dem + " --dem-resolution " + value, "--dem-resolution must be a positive number of metres");
    expect_failure(dem + " --dem-resolution 0.001", "over the limit");
    expect_failure("--dem-resolution 10", "--dem-resolution needs --dem");
}

// GDAL is a module beside the program (osmparse_dem_reader.so), loaded only for --dem: a program
// without it still parses, and says what is missing when asked for a DEM.
TEST_F(TerrainCli, WithoutGdalsModuleOnlyTheDemFails) {
    fs::copy_file(osmparse_binary(), dir_.file("osmparse"));
    fs::permissions(dir_.file("osmparse"), fs::perms::owner_all);
    const std::string program = quoted(dir_.file("osmparse")) + " " + quoted(dir_.file("town.osm"));
    EXPECT_EQ(run_command(program + " -q -o " + quoted(dir_.file("flat.scene"))).exit_code, 0);
    const CommandResult r = run_command(program + " --dem " + quoted(dir_.file("N49E008.hgt")) + " -o " +
                                        quoted(dir_.file("hilly.scene")));
    EXPECT_NE(r.exit_code, 0);
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("--dem needs GDAL's module beside the program"), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_.file("hilly.scene")));
}

// covered=* roads and paths stay drawn at the ground: with --dem each covered way is counted in
// the report, without it the scene is byte for byte what it is without the tags.
TEST_F(TerrainCli, CoveredWaysAreCountedWithADemOnly) {
    std::string plain = kTown;
    plain.replace(plain.find("</osm>"), 6, R"(  <node id="7" lat="49.4995" lon="8.4980"/>
  <node id="8" lat="49.4995" lon="8.5030"/>
  <way id="12"><nd ref="7"/><nd ref="8"/><tag k="highway" v="footway"/></way>
</osm>
)");
    std::string covered = plain;
    covered.replace(covered.find(R"(v="residential"/>)"), 17, R"(v="residential"/><tag k="covered" v="yes"/>)");
    covered.replace(covered.find(R"(v="footway"/>)"), 13, R"(v="footway"/><tag k="covered" v="arcade"/>)");
    // One file name in two folders: the header names the input.
    fs::create_directories(dir_.file("plain"));
    fs::create_directories(dir_.file("covered"));
    write_text(dir_.file("plain/town.osm"), plain);
    write_text(dir_.file("covered/town.osm"), covered);
    auto run = [&](const std::string& folder, const std::string& args) {
        return run_command(quoted(osmparse_binary()) + " " + quoted(dir_.file(folder + "/town.osm")) + " " + args);
    };
    const std::string dem = "--dem " + quoted(dir_.file("N49E008.hgt"));
    const std::string note = "covered: drawn at the ground under what covers it";
    const CommandResult r = run("covered", dem + " -o " + quoted(dir_.file("covered.scene")));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    size_t notes = 0;
    for (size_t at = r.err.find(note); at != std::string::npos; at = r.err.find(note, at + 1)) ++notes;
    EXPECT_EQ(notes, 2u) << "one under road ways, one under path ways: " << r.err;
    const CommandResult p = run("plain", dem + " -o " + quoted(dir_.file("plain.scene")));
    ASSERT_EQ(p.exit_code, 0) << p.err;
    EXPECT_EQ(p.err.find(note), std::string::npos) << p.err;

    const CommandResult flat = run("covered", "-o " + quoted(dir_.file("covered_flat.scene")));
    ASSERT_EQ(flat.exit_code, 0) << flat.err;
    EXPECT_EQ(flat.err.find(note), std::string::npos) << "no note without a field: " << flat.err;
    ASSERT_EQ(run("plain", "-q -o " + quoted(dir_.file("plain_flat.scene"))).exit_code, 0);
    EXPECT_EQ(read_text(dir_.file("covered_flat.scene")), read_text(dir_.file("plain_flat.scene")));
}

// The farm's tiles (docs/farm.md): parsed in one frame with one --dem-resolution, each over its own
// extract, render joins their terrain into one field over both, at the tiles' own altitudes.
TEST_F(TerrainCli, TilesParsedWithOneResolutionAreJoinedByRender) {
    // A second extract east of the town: its field starts further east, and higher on the slope.
    write_text(dir_.file("east.osm"), R"(<?xml version="1.0" encoding="UTF-8"?>
<osm version="0.6">
  <node id="21" lat="49.5000" lon="8.5200"/>
  <node id="22" lat="49.5000" lon="8.5203"/>
  <node id="23" lat="49.5002" lon="8.5203"/>
  <node id="24" lat="49.5002" lon="8.5200"/>
  <way id="30"><nd ref="21"/><nd ref="22"/><nd ref="23"/><nd ref="24"/><nd ref="21"/><tag k="building" v="yes"/></way>
</osm>
)");
    const std::string dem = " --dem " + quoted(dir_.file("N49E008.hgt")) + " --origin 49.5,8.5 -q";
    auto tile = [&](const std::string& osm, const std::string& resolution, const std::string& scene) {
        const CommandResult r = run_command(quoted(osmparse_binary()) + " " + quoted(dir_.file(osm)) + dem +
                                            " --dem-resolution " + resolution + " -o " + quoted(dir_.file(scene)));
        ASSERT_EQ(r.exit_code, 0) << r.err;
    };
    tile("town.osm", "30", "west.scene");
    tile("east.osm", "30", "east.scene");
    tile("east.osm", "20", "east20.scene");
    auto heights = [](const std::string& info, double* lowest, double* highest) {
        const size_t at = info.find("terrain_heights: ");
        ASSERT_NE(at, std::string::npos) << info;
        ASSERT_EQ(std::sscanf(info.c_str() + at, "terrain_heights: %lf - %lf", lowest, highest), 2) << info;
    };
    double west_low, west_high, east_low, east_high, low, high;
    heights(render("--print-scene-info " + quoted(dir_.file("west.scene"))).out, &west_low, &west_high);
    heights(render("--print-scene-info " + quoted(dir_.file("east.scene"))).out, &east_low, &east_high);
    ASSERT_GT(east_high, west_high + 20);  // the slope rises east: the extracts' fields differ
    const CommandResult joined =
        render("--print-scene-info " + quoted(dir_.file("west.scene")) + " " + quoted(dir_.file("east.scene")));
    ASSERT_EQ(joined.exit_code, 0) << joined.err;
    heights(joined.out, &low, &high);
    EXPECT_NEAR(low, west_low, 0.01);
    EXPECT_NEAR(high, east_high, 0.01);
    // Another node spacing is another grid: one line, nothing written.
    const CommandResult refused = render(quoted(dir_.file("west.scene")) + " " + quoted(dir_.file("east20.scene")) +
                                         " -q -o " + quoted(dir_.file("joined.png")));
    EXPECT_NE(refused.exit_code, 0);
    EXPECT_EQ(count_lines(refused.err), 1) << refused.err;
    EXPECT_NE(refused.err.find("--dem-resolution"), std::string::npos) << refused.err;
    EXPECT_FALSE(fs::exists(dir_.file("joined.png")));
}
