// Trees: tags and their fallbacks, tree rows, the forest scatter keeping off roads,
// buildings and water, --trees modes, determinism; on real extracts no tree in a building
// or on a road.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

#include "common/scene_io.h"
#include "osmparse/map/place_trees.h"
#include "osmparse/pipeline.h"
#include "osmparse/polygons/polygon_overlap.h"
#include "tests/osmparse/parse_quietly.h"

using namespace citygen;
using citygen::test::parse_quietly;

namespace {

Scene parse(const std::string& path, ParseReport& report, TreeMode mode = TreeMode::All) {
    ParseParams params;
    params.trees.mode = mode;
    return parse_quietly(path, report, params);
}

std::string fixture(const std::string& name) { return std::string(CITYGEN_SOURCE_DIR) + "/tests/data/map_" + name + ".osm"; }

size_t count(const Scene& s, TreeSource source) {
    size_t n = 0;
    for (const Tree& t : s.trees) n += t.source == source;
    return n;
}

// Trees standing in a building, on a road quad or joint, or in water.
size_t misplaced(const Scene& s) {
    const BuildingIndex buildings(s.buildings);
    std::vector<Building> surface;
    for (const RoadEdge& r : s.roads) surface.push_back({r.osm, r.quad, {}, 0, 0, 0, {}, {}, false});
    for (const Joint& j : s.joints) surface.push_back({j.osm, j.polygon, {}, 0, 0, 0, {}, {}, false});
    const BuildingIndex roads(surface);
    size_t bad = 0;
    for (const Tree& t : s.trees) {
        bool wrong = buildings.contains(t.position) || roads.contains(t.position);
        for (const LandCover& c : s.land_cover) {
            if (c.cover != LandCoverClass::Water && c.cover != LandCoverClass::Sea) continue;
            bool in_hole = false;
            for (const Ring& h : c.holes) in_hole = in_hole || point_in_ring(t.position, h);
            wrong = wrong || (point_in_ring(t.position, c.outer) && !in_hole);
        }
        bad += wrong;
    }
    return bad;
}

OsmTags tags(std::vector<std::pair<std::string, std::string>> entries) {
    OsmTags t;
    t.entries = std::move(entries);
    return t;
}


// A point of the fixture's local metres (make_map_fixtures.py: around 43.7N 7.4E) in the
// scene's coordinates (whose origin is the centre of the data).
Vec2 at(const Scene& s, double x, double y) {
    const Projection projection(s.header.origin_lat, s.header.origin_lon);
    const double m_lat = 111320.0, m_lon = 111320.0 * std::cos(43.7 * kPi / 180);
    return projection.to_local(43.7 + y / m_lat, 7.4 + x / m_lon);
}

}  // namespace

TEST(TreeTags, HeightCrownAndLeafTypeFromTagsElseDefaults) {
    ParseReport report;
    Tree t = tree_from_tags(tags({{"height", "12"}, {"diameter_crown", "6"}, {"leaf_type", "needleleaved"}}), report,
                            ReportKind::MappedTrees);
    EXPECT_DOUBLE_EQ(t.height, 12);
    EXPECT_DOUBLE_EQ(t.crown_diameter, 6);
    EXPECT_EQ(t.leaf_type, LeafType::Needleleaved);
    t = tree_from_tags(tags({{"est_height", "8 m"}}), report, ReportKind::MappedTrees);
    EXPECT_DOUBLE_EQ(t.height, 8);
    EXPECT_EQ(t.leaf_type, LeafType::Broadleaved);
    t = tree_from_tags(tags({{"height", "-3"}, {"diameter_crown", "1e9"}}), report, ReportKind::MappedTrees);
    EXPECT_DOUBLE_EQ(t.height, 10);
    EXPECT_DOUBLE_EQ(t.crown_diameter, 7);
    EXPECT_EQ(report.note_count(ReportKind::MappedTrees, ReportReason::TreeHeightUnusable), 1);
    EXPECT_EQ(report.note_count(ReportKind::MappedTrees, ReportReason::CrownDiameterUnusable), 1);
    t = tree_from_tags(tags({{"height", "banana"}}), report, ReportKind::MappedTrees);
    EXPECT_DOUBLE_EQ(t.height, 10);
}

TEST(Trees, FixtureHasMappedRowAndForestTreesNoneOnTheRoadOrInTheHouseOrPond) {
    ParseReport report;
    const Scene s = parse(fixture("trees"), report);
    EXPECT_EQ(count(s, TreeSource::Mapped), 2u);
    // A 160 m row at 8 m spacing: 20 trees.
    EXPECT_EQ(count(s, TreeSource::Row), 20u);
    EXPECT_GT(count(s, TreeSource::Scattered), 500u);
    EXPECT_EQ(misplaced(s), 0u);
    // Poisson-disk: no two scattered trees closer than the spacing.
    const double r = TreeParams{}.forest_spacing;
    for (size_t i = 0; i < s.trees.size(); ++i)
        for (size_t j = i + 1; j < s.trees.size(); ++j)
            if (s.trees[i].source == TreeSource::Scattered && s.trees[j].source == TreeSource::Scattered) {
                ASSERT_GE(length(s.trees[i].position - s.trees[j].position), r);
            }
    // Something was kept out: there are trees on both sides of the road but none near its centreline.
    const double road_y = at(s, 0, -20).y;
    size_t north = 0, south = 0;
    for (const Tree& t : s.trees) {
        if (t.source != TreeSource::Scattered) continue;
        EXPECT_GT(std::fabs(t.position.y - road_y), 3.0);
        north += t.position.y > road_y;
        south += t.position.y < road_y;
    }
    EXPECT_GT(north, 100u);
    EXPECT_GT(south, 100u);
}

TEST(Trees, ModesNoneAndMappedLeaveOutWhatTheySay) {
    ParseReport report;
    EXPECT_TRUE(parse(fixture("trees"), report, TreeMode::None).trees.empty());
    const Scene mapped = parse(fixture("trees"), report, TreeMode::Mapped);
    EXPECT_EQ(count(mapped, TreeSource::Scattered), 0u);
    EXPECT_EQ(count(mapped, TreeSource::Mapped) + count(mapped, TreeSource::Row), mapped.trees.size());
    EXPECT_EQ(mapped.trees.size(), 22u);
}

TEST(Trees, SameSeedSameTreesOtherSeedOtherScatter) {
    ParseReport report;
    const Scene a = parse(fixture("trees"), report), b = parse(fixture("trees"), report);
    EXPECT_EQ(encode_scene(a), encode_scene(b));
    ParseJob job;
    job.input = fixture("trees");
    job.quiet = true;
    job.params.seed = 7;
    const Scene c = parse_osm_to_scene(job, report);
    ASSERT_EQ(a.trees.size() > 30 && c.trees.size() > 30, true);
    EXPECT_NE(a.trees.back().position, c.trees.back().position);
}

TEST(Trees, MonacoHasNoTreeInABuildingOnARoadOrInWater) {
    // Kaiserslautern (4,100 trees) was checked by hand; ctest keeps to Monaco for time.
    for (const char* name : {"monaco.osm.pbf"}) {
        const std::string path = std::string(CITYGEN_SHARED_DATA_DIR) + "/" + name;
        if (!std::filesystem::exists(path)) continue;
        ParseReport report;
        const Scene s = parse(path, report);
        EXPECT_GT(s.trees.size(), 400u) << name;
        EXPECT_EQ(misplaced(s), 0u) << name;
    }
}
