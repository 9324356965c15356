// osmparse --origin and --keep-inside (the farm's tiles, docs/farm.md) through the program: the
// origin given is the scene's; two tiles that share an edge keep every object once between
// them; bad values get one line and a non-zero exit, and nothing is written.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <regex>
#include <sstream>
#include <vector>

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

CommandResult gather(const std::string& args, const std::string& statistics) {
    return run_command(quoted(osmparse_binary()) + " " + quoted(kExample) + " -q " + args +
                       " --write-region-statistics " + quoted(statistics));
}

// The records of a statistics file, sorted, with the roof counts summed per group ("roofs GROUP
// TAGGED PITCHED" in each part), without the parts' first and last lines.
std::vector<std::string> records(const std::string& text) {
    std::vector<std::string> out;
    std::map<int, std::pair<long, long>> roofs;
    std::stringstream in(text);
    for (std::string line; std::getline(in, line);) {
        std::stringstream fields(line);
        std::string kind;
        fields >> kind;
        if (kind == "roofs") {
            int group = 0;
            long tagged = 0, pitched = 0;
            fields >> group >> tagged >> pitched;
            roofs[group].first += tagged;
            roofs[group].second += pitched;
        } else if (kind != "citygen-region-statistics" && kind != "end") {
            out.push_back(line);
        }
    }
    for (const auto& [group, counts] : roofs)
        out.push_back("roofs " + std::to_string(group) + " " + std::to_string(counts.first) + " " + std::to_string(counts.second));
    std::sort(out.begin(), out.end());
    return out;
}

// Two tiles' statistics are the whole's, and a parse reading the whole's own statistics is the
// parse without them, to the byte.
TEST(TileOptionsCli, TwoTilesGatherTheWholesStatistics) {
    TempDir dir;
    const std::string origin = "--origin 52.4737,13.4399 ";
    ASSERT_EQ(gather(origin, dir.file("whole.stats")).exit_code, 0);
    ASSERT_EQ(gather(origin + "--keep-inside -90,-180,90,13.4399", dir.file("west.stats")).exit_code, 0);
    ASSERT_EQ(gather(origin + "--keep-inside -90,13.4399,90,180", dir.file("east.stats")).exit_code, 0);
    const std::vector<std::string> whole = records(read_text(dir.file("whole.stats")));
    const std::vector<std::string> west = records(read_text(dir.file("west.stats")));
    EXPECT_GT(west.size(), 0u);
    EXPECT_LT(west.size(), whole.size());
    EXPECT_EQ(records(read_text(dir.file("west.stats")) + read_text(dir.file("east.stats"))), whole);

    ASSERT_EQ(parse(origin, dir.file("plain.scene")).exit_code, 0);
    ASSERT_EQ(parse(origin + "--region-statistics " + quoted(dir.file("whole.stats")), dir.file("read.scene")).exit_code, 0);
    EXPECT_EQ(read_text(dir.file("plain.scene")), read_text(dir.file("read.scene")));
    // The tiles' files given one by one are summed: the same scene.
    ASSERT_EQ(parse(origin + "--region-statistics " + quoted(dir.file("west.stats")) + " --region-statistics " +
                        quoted(dir.file("east.stats")),
                    dir.file("tiles.scene"))
                  .exit_code,
              0);
    EXPECT_EQ(read_text(dir.file("plain.scene")), read_text(dir.file("tiles.scene")));
    // One tile's alone is not the region's: its heights differ.
    ASSERT_EQ(parse(origin + "--region-statistics " + quoted(dir.file("west.stats")), dir.file("west.scene")).exit_code, 0);
    EXPECT_NE(read_text(dir.file("plain.scene")), read_text(dir.file("west.scene")));
}

TEST(TileOptionsCli, BadStatisticsGetOneLine) {
    TempDir dir;
    const std::string scene = dir.file("out.scene"), statistics = dir.file("region.stats");
    write_text(scene, "previous");
    ASSERT_EQ(gather("", statistics).exit_code, 0);
    const std::string good = read_text(statistics);
    write_text(dir.file("cut.stats"), good.substr(0, good.size() - 4));
    write_text(dir.file("garbage.stats"), "citygen-region-statistics 1\ntagged 9 1 yes\nend 1\n");
    for (const std::string& args :
         {"--region-statistics " + quoted(dir.file("cut.stats")), "--region-statistics " + quoted(dir.file("garbage.stats")),
          "--region-statistics " + quoted(dir.file("missing.stats")), "--region-statistics " + quoted(dir.path()),
          "--write-region-statistics " + quoted(dir.file("x.stats")),  // with -o: one output or the other
          "--write-region-statistics " + quoted(dir.file("x.stats")) + " --geojson " + quoted(dir.file("x.geojson")),
          "--write-region-statistics " + quoted(dir.file("x.stats")) + " --region-statistics " + quoted(dir.file("cut.stats"))}) {
        const CommandResult r = parse(args, scene);
        EXPECT_NE(r.exit_code, 0) << args;
        EXPECT_EQ(count_lines(r.err), 1) << args << ": " << r.err;
        EXPECT_EQ(r.err.rfind("osmparse: ", 0), 0u) << r.err;
        EXPECT_EQ(r.err.find("unexpected"), std::string::npos) << "a clear line: " << r.err;
        EXPECT_EQ(read_text(scene), "previous") << args;
    }
    // Writing the statistics over the file they are read from is refused, and the file kept.
    const CommandResult r = gather("--region-statistics " + quoted(statistics), statistics);
    EXPECT_NE(r.exit_code, 0);
    EXPECT_EQ(read_text(statistics), good);
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
