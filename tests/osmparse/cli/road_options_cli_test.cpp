// Road options on the command line reach the stages.
#include <gtest/gtest.h>

#include "common/scene_io.h"
#include "tests/test_support.h"

using namespace citygen;
using namespace citygen::test;

TEST(RoadCli, RoadClassesAndMinWidthOptions) {
    TempDir dir;
    const std::string input = quoted(source_path("tests/data/road_dead_end.osm"));
    ASSERT_EQ(run_command(quoted(osmparse_binary()) + " -q " + input + " -o " + quoted(dir.file("all.scene"))).exit_code, 0);
    ASSERT_EQ(run_command(quoted(osmparse_binary()) + " -q --road-classes residential " + input + " -o " +
                          quoted(dir.file("res.scene")))
                  .exit_code,
              0);
    const Scene all = load_scene(dir.file("all.scene"));
    const Scene res = load_scene(dir.file("res.scene"));
    EXPECT_EQ(all.roads.size(), 3u);
    EXPECT_EQ(all.joints.size(), 1u);
    // Without the service road the street is one straight edge and has no junction.
    ASSERT_EQ(res.roads.size(), 1u);
    EXPECT_EQ(res.roads[0].road_class, RoadClass::Residential);
    EXPECT_TRUE(res.joints.empty());

    // The building brushed by the road: with a minimum width above what fits, it is dropped.
    const std::string brushing = quoted(source_path("tests/data/road_brushing_building.osm"));
    ASSERT_EQ(run_command(quoted(osmparse_binary()) + " -q --road-min-width 5 " + brushing + " -o " +
                          quoted(dir.file("b.scene")))
                  .exit_code,
              0);
    EXPECT_TRUE(load_scene(dir.file("b.scene")).roads.empty());
}
