// The road network invariants on every real extract in the shared data folder (skipped
// when it is absent): quads convex with positive area, joints simple, no road or joint
// surface inside a building, lamps outside roads, joints and buildings, quads meeting
// their joints edge to edge (up to counted leftovers).
#include <sys/stat.h>

#include <gtest/gtest.h>

#include "osmparse/pipeline.h"
#include "tests/osmparse/parse_quietly.h"
#include "tests/osmparse/roads/road_checks.h"

using namespace citygen;
using citygen::test::parse_quietly;

namespace {

bool exists(const std::string& path) {
    struct stat st {};
    return ::stat(path.c_str(), &st) == 0;
}

// Quad ends meeting their joint with a hole over 1 cm or an overlap over 0.01 m^2: the
// layout still fails on a few tangles of short edges. The counts measured when the
// limits were set; they may only go down.
struct JoinLimits {
    int gaps = 0, overlaps = 0;
    int sidewalks_on_road = 0;  // sidewalk pieces left on a road by more than 0.01 m^2
};

void check_extract(const std::string& relative, JoinLimits limits) {
    const std::string path = std::string(CITYGEN_SHARED_DATA_DIR) + "/" + relative;
    if (!exists(path)) GTEST_SKIP() << path << " not present";
    ParseReport report;
    const Scene scene = parse_quietly(path, report);
    EXPECT_GT(scene.roads.size(), 0u);
    const RoadCheckCounts c = check_road_network(scene, false);
    std::printf("%s: %d quads (%d bad), %d joints (%d bad), %zu sidewalks (%d bad, %d touching a road), %zu lamps (%d inside), "
                "%d building overlaps, quad/joint: %d gaps > 1 cm, %d overlaps > 0.01 m2\n",
                relative.c_str(), c.quads, c.bad_quads, c.joints, c.bad_joints, scene.sidewalks.size(),
                c.sidewalks_bad, c.sidewalks_on_road, scene.lamps.size(), c.lamps_inside, c.building_overlaps, c.quad_joint_gaps,
                c.quad_joint_overlaps);
    EXPECT_LE(c.quad_joint_gaps, limits.gaps) << "holes between quads and joints";
    EXPECT_LE(c.quad_joint_overlaps, limits.overlaps) << "quads overlapping their joint";
    EXPECT_LE(c.sidewalks_on_road, limits.sidewalks_on_road) << "sidewalk pieces on a road";
    // osmparse counts the same cases in its report.
    EXPECT_EQ(report.note_count(ReportKind::RoadJoints, ReportReason::HoleBeyondQuadEnd), c.quad_joint_gaps);
    EXPECT_EQ(report.note_count(ReportKind::RoadJoints, ReportReason::QuadOverlapsJoint), c.quad_joint_overlaps);
}

}  // namespace

TEST(RoadRealData, Monaco) { check_extract("monaco.osm.pbf", {18, 13, 14}); }
TEST(RoadRealData, MonacoXml) { check_extract("monaco.osm.bz2", {18, 13, 14}); }
TEST(RoadRealData, Neukolln) { check_extract("osm2streets/neukolln/input.osm", {0, 0}); }
TEST(RoadRealData, MontlakeRoundabout) { check_extract("osm2streets/montlake_roundabout/input.osm", {1, 0, 2}); }
TEST(RoadRealData, QuadIntersection) { check_extract("osm2streets/quad_intersection/input.osm", {2, 0}); }
TEST(RoadRealData, SeattleTriangle) { check_extract("osm2streets/seattle_triangle/input.osm", {0, 0}); }
TEST(RoadRealData, TinyRoundabout) { check_extract("osm2streets/tiny_roundabout/input.osm", {0, 0}); }
