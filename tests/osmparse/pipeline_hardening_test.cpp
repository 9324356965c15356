// The defects of issue 8 in the parser: the building index's cost, rounding under
// vectorization, and the same scene bytes from every compiler.
#include <gtest/gtest.h>

#include <filesystem>

#include "common/scene_io.h"
#include "osmparse/buildings/infer_heights.h"
#include "osmparse/pipeline.h"
#include "osmparse/polygons/clean_footprint.h"
#include "osmparse/polygons/polygon_overlap.h"
#include "tests/test_scenes.h"
#include "tests/test_support.h"

using namespace citygen;
using namespace citygen::test;

// Defect 2: the grid allocated every cell of an object's bounding box.
TEST(Hardening, BuildingIndexCostDoesNotGrowWithExtent) {
    std::vector<Building> buildings{box_building(0, 0, 10, 10), box_building(-5e5, -5e5, 5e5, 5e5),
                                    box_building(100, 100, 110, 110)};
    const BuildingIndex index(buildings);
    EXPECT_LE(index.cell_count(), 8u);  // 20,000 x 20,000 cells before
    EXPECT_EQ(index.near(bounds_of(buildings[0].outer)), (std::vector<uint32_t>{0, 1}));
    Box2 everything;
    everything.extend({-1e7, -1e7});
    everything.extend({1e7, 1e7});
    EXPECT_EQ(index.near(everything), (std::vector<uint32_t>{0, 1, 2}));  // 4e11 cells: scanned, not walked
    EXPECT_TRUE(index.contains({3e5, 3e5}));
}

// Defect 9: gcc 12 -O2 dropped the conversion when it vectorized a loop of these.
TEST(Hardening, RoundingToStoredPrecisionSurvivesVectorizedLoops) {
    std::vector<Vec2> points;
    for (int i = 0; i < 1000; ++i) points.push_back({1234.56789 + i * 0.001234567, -987.654321 - i * 0.007654321});
    std::vector<Vec2> rounded(points.size());
    for (size_t i = 0; i < points.size(); ++i) rounded[i] = round_to_stored_precision(points[i]);
    for (size_t i = 0; i < points.size(); ++i) {
        EXPECT_EQ(rounded[i].x, static_cast<double>(static_cast<float>(points[i].x)));
        EXPECT_EQ(rounded[i].y, static_cast<double>(static_cast<float>(points[i].y)));
    }
}

// Defect 9 and the compiler's argument order: the goldens are written by gcc; every other
// build (the clang ASan build in CI, -O1) must produce the same bytes, not just the same
// geometry. Failed under clang before the rounding went through a volatile float and
// encode_scene stopped depending on the order of evaluation of arguments.
TEST(Hardening, FixturesParseToTheGoldenBytes) {
    int compared = 0;
    for (const auto& entry : std::filesystem::directory_iterator(source_path("tests/data"))) {
        if (entry.path().extension() != ".osm") continue;
        const std::string name = entry.path().stem().string();
        const std::string golden = source_path("tests/golden/" + name + ".scene");
        ParseJob job;
        job.input = entry.path().string();
        job.quiet = true;
        ParseReport report;
        const std::vector<uint8_t> bytes = encode_scene(parse_osm_to_scene(job, report));
        EXPECT_EQ(std::string(bytes.begin(), bytes.end()), read_text(golden)) << name << ": other bytes than " << golden;
        ++compared;
    }
    EXPECT_GE(compared, 10);
}

// The land use grid held every 250 m cell of each area's box: one stray node of a landuse=
// polygon 500 km away made millions of cells (a stall, gigabytes). Such an area is left out and
// counted; a normal one beside it is still used.
TEST(Hardening, LandUseAreaWithAStrayNodeIsLeftOutAndCounted) {
    TempDir dir;
    const std::string input = dir.file("stray.osm");
    write_text(input, R"(<?xml version="1.0" encoding="UTF-8"?>
<osm version="0.6">
  <node id="1" lat="50.0000" lon="8.0000"/>
  <node id="2" lat="50.0000" lon="8.0100"/>
  <node id="3" lat="50.0100" lon="8.0100"/>
  <node id="4" lat="54.0000" lon="14.0000"/>
  <node id="5" lat="50.0100" lon="8.0000"/>
  <node id="11" lat="50.0020" lon="8.0020"/>
  <node id="12" lat="50.0020" lon="8.0030"/>
  <node id="13" lat="50.0030" lon="8.0030"/>
  <node id="14" lat="50.0030" lon="8.0020"/>
  <way id="100"><nd ref="1"/><nd ref="2"/><nd ref="4"/><nd ref="5"/><nd ref="1"/><tag k="landuse" v="residential"/></way>
  <way id="101"><nd ref="1"/><nd ref="2"/><nd ref="3"/><nd ref="1"/><tag k="landuse" v="industrial"/></way>
  <way id="200"><nd ref="11"/><nd ref="12"/><nd ref="13"/><nd ref="14"/><nd ref="11"/><tag k="building" v="yes"/></way>
</osm>
)");
    ParseJob job;
    job.input = input;
    job.quiet = true;
    ParseReport report;
    const Scene scene = parse_osm_to_scene(job, report);
    EXPECT_EQ(report.note_count(ReportKind::BuildingHeights, ReportReason::LandUseTooLarge), 1);
    ASSERT_EQ(scene.buildings.size(), 1u);
    EXPECT_EQ(scene.buildings[0].height_rule, HeightRule::TypeAndArea);  // an industrial hall: 8 m +-10%
    EXPECT_NEAR(scene.buildings[0].height, 8, 0.81);
}
