// Invariants on every real extract in the shared data folder (skipped when it is absent):
// the parse succeeds, counts are reported, and every stored ring is simple, correctly
// oriented and of positive area. Also: parsing is deterministic to the byte.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>

#include "common/scene_io.h"
#include "osmparse/pipeline.h"
#include "osmparse/polygons/polygon_overlap.h"
#include "osmparse/polygons/ring_is_simple.h"
#include "tests/osmparse/parse_quietly.h"

using namespace citygen;
using citygen::test::parse_quietly;
namespace fs = std::filesystem;

namespace {

const std::string kShared = CITYGEN_SHARED_DATA_DIR;

std::vector<std::string> real_extracts() {
    std::vector<std::string> files;
    if (fs::is_directory(kShared)) {
        for (const char* name : {"monaco.osm.bz2", "monaco.osm.pbf"})
            if (fs::exists(kShared + "/" + name)) files.push_back(name);
        if (fs::is_directory(kShared + "/osm2streets"))
            for (const auto& entry : fs::directory_iterator(kShared + "/osm2streets"))
                if (fs::exists(entry.path() / "input.osm"))
                    files.push_back("osm2streets/" + entry.path().filename().string() + "/input.osm");
    }
    std::sort(files.begin(), files.end());
    if (files.empty()) files.push_back("none");  // one test that reports the skip
    return files;
}

std::string test_name(const testing::TestParamInfo<std::string>& info) {
    std::string name = info.param;
    for (char& c : name)
        if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
    return name;
}

class RealExtract : public testing::TestWithParam<std::string> {
protected:
    std::string path() const { return kShared + "/" + GetParam(); }
    void SetUp() override {
        if (GetParam() == "none") GTEST_SKIP() << "no shared OSM data at " << kShared;
    }
};

}  // namespace

TEST_P(RealExtract, EveryStoredRingIsSimpleOrientedAndPositive) {
    ParseReport report;
    const Scene parsed = parse_quietly(path(), report);
    // Check what is stored (float32 coordinates), not only what was computed.
    const std::vector<uint8_t> bytes = encode_scene(parsed);
    const Scene scene = decode_scene(bytes.data(), bytes.size(), GetParam());

    ASSERT_GT(report.read_count(ReportKind::BuildingAreas), 0);
    ASSERT_FALSE(scene.buildings.empty());
    EXPECT_EQ(report.kept_count(ReportKind::Buildings) + report.kept_count(ReportKind::BuildingParts),
              static_cast<int64_t>(scene.buildings.size()));
    const double min_area = ParseParams{}.buildings.min_area;
    for (const Building& b : scene.buildings) {
        const std::string who = to_string(b.osm);
        ASSERT_TRUE(ring_is_simple(b.outer)) << who;
        EXPECT_GT(signed_area(b.outer), 0) << who << " outer must be counter-clockwise";
        double area = signed_area(b.outer);
        for (const Ring& hole : b.holes) {
            ASSERT_TRUE(ring_is_simple(hole)) << who;
            EXPECT_LT(signed_area(hole), 0) << who << " holes must be clockwise";
            for (Vec2 p : hole) EXPECT_TRUE(point_in_ring(p, b.outer)) << who << " hole outside";
            area += signed_area(hole);
        }
        EXPECT_GE(area, min_area * 0.999) << who;
        EXPECT_GT(b.height, b.min_height) << who;
        EXPECT_GE(b.min_height, 0) << who;
        EXPECT_LE(b.height, 1000) << who;
        EXPECT_GE(b.levels, 1) << who;
    }
    // Paths (format 1.1): convex-or-simple CCW strips; trees: none in a building or on a road.
    for (const PathEdge& p : scene.paths) {
        ASSERT_EQ(p.quad.size(), 4u) << to_string(p.osm);
        EXPECT_TRUE(ring_is_simple(p.quad)) << to_string(p.osm);
        EXPECT_GT(signed_area(p.quad), 0) << to_string(p.osm);
    }
    {
        const BuildingIndex buildings(scene.buildings);
        std::vector<Building> surface;
        for (const RoadEdge& r : scene.roads) surface.push_back({r.osm, r.quad, {}, 0, 0, 0, {}, {}, false});
        for (const Joint& j : scene.joints) surface.push_back({j.osm, j.polygon, {}, 0, 0, 0, {}, {}, false});
        const BuildingIndex roads(surface);
        for (const Tree& t : scene.trees) {
            EXPECT_FALSE(buildings.contains(t.position)) << "tree " << to_string(t.osm) << " in a building";
            EXPECT_FALSE(roads.contains(t.position)) << "tree " << to_string(t.osm) << " on a road";
        }
    }
    // Land cover (format 1.1), as stored: simple, outer counter-clockwise, holes clockwise inside.
    for (const LandCover& c : scene.land_cover) {
        const std::string who = std::string(to_string(c.cover)) + " " + to_string(c.osm);
        ASSERT_TRUE(ring_is_simple(c.outer)) << who;
        EXPECT_GT(signed_area(c.outer), 0) << who;
        for (const Ring& hole : c.holes) {
            ASSERT_TRUE(ring_is_simple(hole)) << who;
            EXPECT_LT(signed_area(hole), 0) << who;
        }
    }
}

TEST_P(RealExtract, ParsingTwiceGivesTheSameBytes) {
    ParseReport first_report, second_report;
    const std::vector<uint8_t> first = encode_scene(parse_quietly(path(), first_report));
    const std::vector<uint8_t> second = encode_scene(parse_quietly(path(), second_report));
    EXPECT_TRUE(first == second);
}

INSTANTIATE_TEST_SUITE_P(SharedData, RealExtract, testing::ValuesIn(real_extracts()), test_name);

TEST(RealExtracts, XmlAndPbfOfMonacoGiveTheSameBuildings) {
    if (!fs::exists(kShared + "/monaco.osm.bz2") || !fs::exists(kShared + "/monaco.osm.pbf"))
        GTEST_SKIP() << "no Monaco extract at " << kShared;
    ParseReport xml_report, pbf_report;
    const Scene xml = parse_quietly(kShared + "/monaco.osm.bz2", xml_report);
    const Scene pbf = parse_quietly(kShared + "/monaco.osm.pbf", pbf_report);
    ASSERT_EQ(xml.buildings.size(), pbf.buildings.size());
    for (size_t i = 0; i < xml.buildings.size(); ++i) {
        EXPECT_EQ(xml.buildings[i].osm, pbf.buildings[i].osm);
        EXPECT_EQ(xml.buildings[i].height, pbf.buildings[i].height);
    }
}
