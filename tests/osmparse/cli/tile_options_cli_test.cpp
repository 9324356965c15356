// osmparse --origin and --keep-inside (the farm's tiles, docs/farm.md) through the program: the
// origin given is the scene's; two tiles that share an edge keep every object once between
// them; bad values get one line and a non-zero exit, and nothing is written.
#include <gtest/gtest.h>

#include <regex>

#include "tests/test_support.h"

using namespace citygen::test;

namespace {

const std::string kExample = source_path("examples/neukolln.osm.bz2");

CommandResult parse(const std::string& args, const std::string& scene) {
    return run_command(quoted(osmparse_binary()) + " " + quoted(kExample) + " -q " + args + " -o " + quoted(scene));
}

// The number after "KEY: " in osmparse --info's output.
long info_count(const std::string& scene, const std::string& key) {
    const CommandResult r = run_command(quoted(osmparse_binary()) + " --info " + quoted(scene));
    std::smatch m;
    if (!std::regex_search(r.out, m, std::regex("\n" + key + ": ([0-9]+)"))) return -1;
    return std::stol(m[1]);
}

TEST(TileOptionsCli, OriginGivenIsTheScenes) {
    TempDir dir;
    ASSERT_EQ(parse("--origin 52.47,13.44", dir.file("a.scene")).exit_code, 0);
    const CommandResult r = run_command(quoted(osmparse_binary()) + " --info " + quoted(dir.file("a.scene")));
    EXPECT_NE(r.out.find("origin: 52.4700000, 13.4400000"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("origin = 52.47,13.44"), std::string::npos) << r.out;
}

TEST(TileOptionsCli, TwoTilesKeepEveryObjectOnce) {
    TempDir dir;
    const std::string origin = "--origin 52.4737,13.4399 ";
    ASSERT_EQ(parse(origin, dir.file("whole.scene")).exit_code, 0);
    ASSERT_EQ(parse(origin + "--keep-inside -90,-180,90,13.4399", dir.file("west.scene")).exit_code, 0);
    ASSERT_EQ(parse(origin + "--keep-inside -90,13.4399,90,180", dir.file("east.scene")).exit_code, 0);
    for (const char* key : {"buildings", "roads", "joints", "lamps", "land_cover", "trees", "paths"}) {
        const long whole = info_count(dir.file("whole.scene"), key);
        const long west = info_count(dir.file("west.scene"), key), east = info_count(dir.file("east.scene"), key);
        ASSERT_GE(whole, 0) << key;
        EXPECT_EQ(west + east, whole) << key;
        if (std::string(key) == "buildings") {
            EXPECT_TRUE(west > 0 && east > 0) << "the cut goes through the town";
        }
    }
}

TEST(TileOptionsCli, BadValuesGetOneLine) {
    TempDir dir;
    const std::string scene = dir.file("out.scene");
    write_text(scene, "previous");
    for (const char* args : {"--origin 91,13", "--origin 52,13,1", "--origin abc", "--origin 52,-181",
                             "--keep-inside 52,13,53,14", "--origin 52,13 --keep-inside 53,13,52,14",
                             "--origin 52,13 --keep-inside 52,13,53"}) {
        const CommandResult r = parse(args, scene);
        EXPECT_NE(r.exit_code, 0) << args;
        EXPECT_EQ(count_lines(r.err), 1) << args << ": " << r.err;
        EXPECT_EQ(r.err.rfind("osmparse: --", 0), 0u) << r.err;
        EXPECT_EQ(read_text(scene), "previous") << args;
    }
}

}  // namespace
