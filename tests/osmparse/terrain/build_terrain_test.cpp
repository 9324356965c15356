// The terrain stage: the sea mask, and the whole parse of Monaco with its SRTM tile (shared data,
// skipped when absent): heights where Monaco's are, the sea at sea level, the file the same.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "common/scene_io.h"
#include "osmparse/pipeline.h"
#include "osmparse/terrain/build_terrain.h"
#include "osmparse/terrain/read_dem.h"
#include "tests/osmparse/parse_quietly.h"
#include "tests/test_support.h"

using namespace citygen;

namespace {

const std::string kMonaco = std::string(CITYGEN_SHARED_DATA_DIR) + "/monaco.osm.pbf";
const std::string kTile = std::string(CITYGEN_SHARED_DATA_DIR) + "/../dem/N43E007.hgt.zip";

bool have_monaco() { return std::filesystem::exists(kMonaco) && std::filesystem::exists(kTile); }

ParseJob monaco_job() {
    ParseJob job;
    job.input = kMonaco;
    job.quiet = true;
    job.params.terrain.dem_files = {kTile};
    return job;
}

double height_at(const Scene& s, double lat, double lon) {
    const Vec2 p = Projection(s.header.origin_lat, s.header.origin_lon).to_local(lat, lon);
    return s.terrain.reference_altitude + s.terrain.at(p.x, p.y);
}

}  // namespace

TEST(SeaMask, NodesInsideTheSeaButNotInItsHoles) {
    DemGrid g;
    g.cell = 10;
    g.nx = g.ny = 11;  // 0..100 m
    LandCover sea{{OsmType::Way, 1}, LandCoverClass::Sea, {{-5, -5}, {105, -5}, {105, 45}, {-5, 45}},
                  {{{35, 15}, {35, 25}, {65, 25}, {65, 15}}}};  // an island
    LandCover park{{OsmType::Way, 2}, LandCoverClass::Green, {{0, 60}, {100, 60}, {100, 100}, {0, 100}}, {}};
    const std::vector<uint8_t> mask = sea_mask(g, {sea, park});
    ASSERT_EQ(mask.size(), g.size());
    EXPECT_EQ(mask[g.index(0, 0)], 1);
    EXPECT_EQ(mask[g.index(10, 4)], 1);
    EXPECT_EQ(mask[g.index(5, 2)], 0);  // the island
    EXPECT_EQ(mask[g.index(3, 2)], 1);
    EXPECT_EQ(mask[g.index(5, 5)], 0);  // above the sea's north shore
    EXPECT_EQ(mask[g.index(5, 8)], 0);  // the park is no sea
    EXPECT_TRUE(sea_mask(g, {park}).empty());
}

TEST(BuildTerrainMonaco, HeightsArePlausibleAndTheSeaIsAtSeaLevel) {
    if (!have_monaco()) GTEST_SKIP() << "no Monaco extract or SRTM tile at " << kTile;
    ParseReport report;
    const Scene s = parse_osm_to_scene(monaco_job(), report);
    const HeightField& t = s.terrain;
    ASSERT_FALSE(t.empty());
    EXPECT_EQ(t.cell, kRoadFitCell);  // finer than SRTM3's 81 m (3 arc-seconds at 43.7 N), for the roads
    EXPECT_LE(t.origin.x, s.header.bounds_min.x);
    EXPECT_GE(t.origin.y + (t.ny - 1) * t.cell, s.header.bounds_max.y);
    EXPECT_EQ(t.reference_altitude, 0);  // the sea is in the scene
    EXPECT_NE(t.vertical_datum.find("EGM96"), std::string::npos);
    const auto [lowest, highest] = std::minmax_element(t.heights.begin(), t.heights.end());
    EXPECT_GE(*lowest, -20);
    EXPECT_LE(*highest, 800);  // the hills above Beausoleil and Cap-d'Ail reach into the extract
    // The buildings of the principality and the towns around: the ground under them.
    std::vector<double> ground;
    for (const Building& b : s.buildings) ground.push_back(t.at(b.outer[0].x, b.outer[0].y));
    std::sort(ground.begin(), ground.end());
    EXPECT_GE(ground.front(), -20);
    EXPECT_LE(ground[ground.size() * 9 / 10], 300);
    EXPECT_GT(ground[ground.size() / 2], 10);  // Monaco climbs from the sea
    EXPECT_NEAR(height_at(s, 43.7314, 7.4200), 55, 35);  // the Rock (Prince's Palace, about 60 m)
    EXPECT_NEAR(height_at(s, 43.7394, 7.4277), 45, 35);  // the Casino, about 45 m
    EXPECT_NEAR(height_at(s, 43.7290, 7.4380), 0, 3);    // the sea off Monte Carlo
    EXPECT_NEAR(height_at(s, 43.7300, 7.4500), 0, 3);
    EXPECT_EQ(report.kept_count(ReportKind::DemFiles), 1);
    EXPECT_EQ(report.kept_count(ReportKind::TerrainNodes), static_cast<int64_t>(t.heights.size()));
}

// The file written part by part holds the field and is the bytes of the whole scene encoded.
TEST(BuildTerrainMonaco, TheFileHoldsTheFieldAndIsTheSceneEncoded) {
    if (!have_monaco()) GTEST_SKIP() << "no Monaco extract or SRTM tile at " << kTile;
    test::TempDir dir;
    ParseJob job = monaco_job();
    job.params.terrain.resolution = 30;
    ParseReport to_file, to_scene;
    parse_osm_to_file(job, to_file, dir.file("monaco.scene"));
    const std::vector<uint8_t> bytes = encode_scene(parse_osm_to_scene(job, to_scene));
    EXPECT_EQ(test::read_text(dir.file("monaco.scene")), std::string(bytes.begin(), bytes.end()));
    const Scene loaded = load_scene(dir.file("monaco.scene"));
    EXPECT_EQ(loaded.terrain.cell, 30);
    EXPECT_GT(loaded.terrain.heights.size(), 10000u);
    const auto kv = std::find(loaded.header.options.begin(), loaded.header.options.end(),
                              std::make_pair(std::string("dem"), std::string("N43E007.hgt.zip")));
    EXPECT_NE(kv, loaded.header.options.end());
}
