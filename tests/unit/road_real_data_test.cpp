// The road network invariants on every real extract in the shared data folder (skipped
// when it is absent): quads convex with positive area, joints simple, no road or joint
// surface inside a building, lamps outside roads, joints and buildings.
#include <sys/stat.h>

#include <gtest/gtest.h>

#include "pipeline.h"
#include "road_checks.h"

using namespace citygen;

namespace {

bool exists(const std::string& path) {
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0;
}

void check_extract(const std::string& relative) {
    const std::string path = std::string(CITYGEN_SHARED_DATA_DIR) + "/" + relative;
    if (!exists(path)) GTEST_SKIP() << path << " not present";
    ParseJob job;
    job.input = path;
    job.quiet = true;
    ParseReport report;
    const Scene scene = parse_osm_to_scene(job, report);
    EXPECT_GT(scene.roads.size(), 0u);
    const RoadCheckCounts c = check_road_network(scene, false);
    std::printf("%s: %d quads (%d bad), %d joints (%d bad), %zu sidewalks (%d bad, %d touching a road), %zu lamps (%d inside), "
                "%d building overlaps, quad/joint: %d gaps > 1 cm, %d overlaps > 0.01 m2\n",
                relative.c_str(), c.quads, c.bad_quads, c.joints, c.bad_joints, scene.sidewalks.size(),
                c.sidewalks_bad, c.sidewalks_on_road, scene.lamps.size(), c.lamps_inside, c.building_overlaps, c.quad_joint_gaps,
                c.quad_joint_overlaps);
}

}  // namespace

TEST(RoadRealData, Monaco) { check_extract("monaco.osm.pbf"); }
TEST(RoadRealData, Neukolln) { check_extract("osm2streets/neukolln/input.osm"); }
TEST(RoadRealData, MontlakeRoundabout) { check_extract("osm2streets/montlake_roundabout/input.osm"); }
TEST(RoadRealData, QuadIntersection) { check_extract("osm2streets/quad_intersection/input.osm"); }
TEST(RoadRealData, SeattleTriangle) { check_extract("osm2streets/seattle_triangle/input.osm"); }
TEST(RoadRealData, TinyRoundabout) { check_extract("osm2streets/tiny_roundabout/input.osm"); }
