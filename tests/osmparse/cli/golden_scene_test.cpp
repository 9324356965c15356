// Golden scene tests: every fixture in tests/data parses to a scene that `osmparse --diff`
// finds equal to tests/golden/NAME.scene. Regenerate on purpose with tests/golden/regenerate.sh.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "tests/test_support.h"

using namespace citygen::test;
namespace fs = std::filesystem;

namespace {

std::vector<std::string> fixture_names() {
    std::vector<std::string> names;
    for (const auto& entry : fs::directory_iterator(source_path("tests/data")))
        if (entry.path().extension() == ".osm") names.push_back(entry.path().stem().string());
    std::sort(names.begin(), names.end());
    return names;
}

class GoldenScene : public testing::TestWithParam<std::string> {};

}  // namespace

TEST_P(GoldenScene, ParsesToTheGoldenScene) {
    const std::string name = GetParam();
    const std::string golden = source_path("tests/golden/" + name + ".scene");
    ASSERT_TRUE(fs::exists(golden)) << golden << " is missing: run tests/golden/regenerate.sh";
    TempDir dir;
    const std::string fresh = dir.file(name + ".scene");
    const CommandResult parse = run_command(quoted(osmparse_binary()) + " --quiet " +
                                            quoted(source_path("tests/data/" + name + ".osm")) + " -o " + quoted(fresh));
    ASSERT_EQ(parse.exit_code, 0) << parse.err;
    EXPECT_TRUE(parse.err.empty()) << "--quiet printed: " << parse.err;
    const CommandResult diff = run_command(quoted(osmparse_binary()) + " --diff " + quoted(golden) + " " + quoted(fresh));
    EXPECT_EQ(diff.exit_code, 0) << "scene differs from " << golden
                                 << " (if intended, run tests/golden/regenerate.sh):\n" << diff.out << diff.err;
}

INSTANTIATE_TEST_SUITE_P(Fixtures, GoldenScene, testing::ValuesIn(fixture_names()),
                         [](const testing::TestParamInfo<std::string>& info) { return info.param; });

TEST(GoldenScenes, EveryGoldenHasItsFixture) {
    const std::vector<std::string> fixtures = fixture_names();
    EXPECT_GE(fixtures.size(), 8u);
    for (const auto& entry : fs::directory_iterator(source_path("tests/golden")))
        if (entry.path().extension() == ".scene")
            EXPECT_TRUE(std::count(fixtures.begin(), fixtures.end(), entry.path().stem().string()))
                << entry.path() << " has no fixture in tests/data";
}

TEST(GoldenScenes, DiffNoticesAChangedScene) {
    // The golden test is only as good as --diff: a scene parsed with another seed (so
    // different random heights) must not match its golden.
    TempDir dir;
    const std::string fresh = dir.file("other_seed.scene");
    ASSERT_EQ(run_command(quoted(osmparse_binary()) + " -q --seed 99 " +
                          quoted(source_path("tests/data/courtyard_multipolygon.osm")) + " -o " + quoted(fresh))
                  .exit_code,
              0);
    const CommandResult diff = run_command(quoted(osmparse_binary()) + " --diff " +
                                           quoted(source_path("tests/golden/courtyard_multipolygon.scene")) + " " +
                                           quoted(fresh));
    EXPECT_EQ(diff.exit_code, 1);
    EXPECT_NE(diff.out.find("parse options differ"), std::string::npos) << diff.out;
    EXPECT_NE(diff.out.find("height changed"), std::string::npos) << diff.out;
}
