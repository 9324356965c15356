// The map's content through the command lines: --info, --geojson and --diff in osmparse,
// --print-scene-info and --print-scene-geometry-info lines per new class in render.
#include <gtest/gtest.h>

#include "tests/test_support.h"

using namespace citygen::test;

namespace {

std::string fixture(const std::string& name) { return source_path("tests/data/map_" + name + ".osm"); }

}  // namespace

TEST(MapContentCli, InfoGeojsonAndGeometryInfoListEveryNewKind) {
    TempDir dir;
    const std::string scene = dir.file("trees.scene"), lanes = dir.file("lanes.scene"), geojson = dir.file("t.geojson");
    ASSERT_EQ(run_command(osmparse_binary() + " -q " + quoted(fixture("trees")) + " -o " + quoted(scene) +
                          " --geojson " + quoted(geojson)).exit_code, 0);
    ASSERT_EQ(run_command(osmparse_binary() + " -q " + quoted(fixture("lanes")) + " -o " + quoted(lanes)).exit_code, 0);

    const CommandResult info = run_command(osmparse_binary() + " --info " + quoted(scene));
    EXPECT_EQ(info.exit_code, 0);
    for (const char* line : {"format_version: 1.2", "land_cover: 2", "land_cover_forest: 1", "land_cover_water: 1",
                             "trees: ", "paths: ", "crossings: "})
        EXPECT_NE(info.out.find(line), std::string::npos) << line << "\n" << info.out;
    const CommandResult lanes_info = run_command(osmparse_binary() + " --info " + quoted(lanes));
    EXPECT_NE(lanes_info.out.find("crossings: 2 (1 zebra, 1 stop lines)"), std::string::npos) << lanes_info.out;

    const std::string text = read_text(geojson);
    for (const char* kind : {"\"kind\":\"land_cover\",\"class\":\"forest\"", "\"kind\":\"tree\"", "\"source\":\"scattered\""})
        EXPECT_NE(text.find(kind), std::string::npos) << kind;

    // --diff sees the new kinds: a scene without trees differs by exactly its trees.
    const std::string bare = dir.file("bare.scene");
    ASSERT_EQ(run_command(osmparse_binary() + " -q " + quoted(fixture("trees")) + " --trees none -o " + quoted(bare)).exit_code, 0);
    const CommandResult diff = run_command(osmparse_binary() + " --diff " + quoted(bare) + " " + quoted(scene));
    EXPECT_EQ(diff.exit_code, 1);
    EXPECT_NE(diff.out.find("added    tree scattered"), std::string::npos) << diff.out.substr(0, 400);

    for (const char* flags : {"", " --procedural"}) {
        const CommandResult geometry = run_command(std::string(CITYGEN_BIN_DIR) + "/render " + quoted(scene) +
                                                   " --print-scene-geometry-info --print-scene-info -q" + flags);
        EXPECT_EQ(geometry.exit_code, 0) << geometry.err;
        for (const char* line : {"primitives_land_cover: ", "primitives_tree: ", "trees: "})
            EXPECT_NE(geometry.out.find(line), std::string::npos) << line << flags << "\n" << geometry.out;
    }
    const std::string paths = dir.file("paths.scene");
    ASSERT_EQ(run_command(osmparse_binary() + " -q " + quoted(fixture("paths")) + " -o " + quoted(paths)).exit_code, 0);
    const CommandResult path_geometry =
        run_command(std::string(CITYGEN_BIN_DIR) + "/render " + quoted(paths) + " --print-scene-geometry-info -q");
    EXPECT_NE(path_geometry.out.find("triangles_path_ballast: 2"), std::string::npos) << path_geometry.out;
}
