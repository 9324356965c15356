// The buildings stage on the hand-made fixtures in tests/data: what each one is for.
#include <gtest/gtest.h>

#include <cmath>

#include "osmparse/pipeline.h"
#include "tests/osmparse/parse_quietly.h"
#include "tests/test_support.h"

using namespace citygen;
using citygen::test::parse_quietly;
using citygen::test::source_path;

namespace {

Scene parse_fixture(const std::string& name, ParseReport& report, ParseParams params = ParseParams{}) {
    return parse_quietly(source_path("tests/data/" + name + ".osm"), report, params);
}

std::vector<const Building*> find(const Scene& scene, OsmType type, int64_t id) {
    std::vector<const Building*> out;
    for (const Building& b : scene.buildings)
        if (b.osm == OsmRef{type, id}) out.push_back(&b);
    return out;
}

double net_area(const Building& b) {
    double a = signed_area(b.outer);
    for (const Ring& h : b.holes) a += signed_area(h);
    return a;
}

}  // namespace

TEST(BuildBuildings, CourtyardMultipolygonKeepsItsHole) {
    ParseReport report;
    const Scene scene = parse_fixture("courtyard_multipolygon", report);
    const auto courtyard = find(scene, OsmType::Relation, 1);
    ASSERT_EQ(courtyard.size(), 1u);
    ASSERT_EQ(courtyard[0]->holes.size(), 1u);
    EXPECT_NEAR(net_area(*courtyard[0]), 40 * 30 - 20 * 14, 1.0);
    EXPECT_DOUBLE_EQ(courtyard[0]->height, 15);  // 5 levels
    EXPECT_EQ(courtyard[0]->height_source, HeightSource::Levels);
    EXPECT_EQ(courtyard[0]->type, "apartments");
    const auto house = find(scene, OsmType::Way, 103);
    ASSERT_EQ(house.size(), 1u);
    EXPECT_EQ(house[0]->height_source, HeightSource::Random);
    EXPECT_EQ(scene.buildings.size(), 2u);
}

TEST(BuildBuildings, PartsReplaceTheOutlineTheyLieIn) {
    ParseReport report;
    const Scene scene = parse_fixture("building_with_parts", report);
    EXPECT_TRUE(find(scene, OsmType::Way, 101).empty()) << "outline with parts must be replaced";
    EXPECT_TRUE(find(scene, OsmType::Way, 104).empty()) << "building:part=roof is an ignored type";
    const auto tall = find(scene, OsmType::Way, 102);
    const auto low = find(scene, OsmType::Way, 103);
    const auto plain = find(scene, OsmType::Way, 105);
    ASSERT_EQ(tall.size(), 1u);
    ASSERT_EQ(low.size(), 1u);
    ASSERT_EQ(plain.size(), 1u);
    EXPECT_TRUE(tall[0]->is_part);
    EXPECT_DOUBLE_EQ(tall[0]->height, 30);
    EXPECT_EQ(tall[0]->levels, 10);
    EXPECT_DOUBLE_EQ(low[0]->height, 12);
    EXPECT_DOUBLE_EQ(low[0]->min_height, 3);
    EXPECT_EQ(low[0]->levels, 3);
    EXPECT_FALSE(plain[0]->is_part);
    EXPECT_DOUBLE_EQ(plain[0]->height, 6);
    EXPECT_EQ(report.dropped_count(ReportKind::Buildings, ReportReason::ReplacedByParts), 1);
    EXPECT_EQ(report.kept_count(ReportKind::BuildingParts), 2);
}

TEST(BuildBuildings, ClippedWayIsCountedNotFatal) {
    ParseReport report;
    const Scene scene = parse_fixture("clipped_way", report);
    EXPECT_TRUE(find(scene, OsmType::Way, 101).empty());
    EXPECT_EQ(find(scene, OsmType::Way, 103).size(), 1u);
    EXPECT_EQ(report.dropped_count(ReportKind::BuildingWays, ReportReason::NodesMissing), 1);
    EXPECT_EQ(report.note_count(ReportKind::HighwayWays, ReportReason::ClippedAtEdge), 1);
}

TEST(BuildBuildings, RelationWithMissingMemberIsCountedNotFatal) {
    ParseReport report;
    const Scene scene = parse_fixture("missing_member", report);
    EXPECT_TRUE(find(scene, OsmType::Relation, 2).empty());
    const auto complete = find(scene, OsmType::Relation, 3);
    ASSERT_EQ(complete.size(), 1u);
    EXPECT_EQ(complete[0]->holes.size(), 1u);
    EXPECT_DOUBLE_EQ(complete[0]->height, 12);
    EXPECT_EQ(report.dropped_count(ReportKind::BuildingRelations, ReportReason::MembersMissing), 1);
}

TEST(BuildBuildings, BrokenOutlinesAreRepairedOrDropped) {
    ParseReport report;
    const Scene scene = parse_fixture("bow_tie", report);
    const auto bow_tie = find(scene, OsmType::Way, 101);
    ASSERT_EQ(bow_tie.size(), 2u) << "a bow-tie becomes two triangles";
    for (const Building* b : bow_tie) {
        EXPECT_EQ(b->outer.size(), 3u);
        EXPECT_NEAR(signed_area(b->outer), 100, 0.5);
        EXPECT_EQ(b->height, bow_tie[0]->height) << "pieces share the building's height";
    }
    const auto clockwise = find(scene, OsmType::Way, 102);
    ASSERT_EQ(clockwise.size(), 1u);
    EXPECT_EQ(clockwise[0]->outer.size(), 4u) << "duplicate and collinear vertices dropped";
    EXPECT_NEAR(signed_area(clockwise[0]->outer), 15 * 20, 0.5);
    EXPECT_TRUE(find(scene, OsmType::Way, 103).empty()) << "sliver";
    EXPECT_TRUE(find(scene, OsmType::Way, 106).empty()) << "building=ruins is ignored";
    EXPECT_EQ(find(scene, OsmType::Relation, 4).size(), 2u);
    EXPECT_EQ(report.dropped_count(ReportKind::Buildings, ReportReason::SliverBelowMinArea), 1);
    EXPECT_EQ(report.dropped_count(ReportKind::Buildings, ReportReason::IgnoredType), 1);
    EXPECT_EQ(report.note_count(ReportKind::Buildings, ReportReason::Repaired), 1);
}

TEST(BuildBuildings, HeightsInFeetAndLevels) {
    ParseReport report;
    const Scene scene = parse_fixture("heights_in_feet", report);
    ASSERT_EQ(scene.buildings.size(), 6u);
    auto only = [&](int64_t id) {
        const auto found = find(scene, OsmType::Way, id);
        EXPECT_EQ(found.size(), 1u) << id;
        return found.empty() ? Building{} : *found[0];
    };
    EXPECT_NEAR(only(101).height, 40 * 0.3048, 1e-6);
    EXPECT_NEAR(only(102).height, 66 * 0.3048 + 6 * 0.0254, 1e-6);
    EXPECT_NEAR(only(102).min_height, 10 * 0.3048, 1e-6);
    EXPECT_DOUBLE_EQ(only(103).height, 12.5);
    EXPECT_DOUBLE_EQ(only(104).height, 21);
    EXPECT_EQ(only(105).height_source, HeightSource::Random);  // 5000 m is absurd
    EXPECT_DOUBLE_EQ(only(106).eaves_height(), 9);              // "tall" ignored, 3 levels (+ any roof)
    EXPECT_EQ(report.note_count(ReportKind::Buildings, ReportReason::BadHeightTag), 2);
}

TEST(BuildBuildings, IgnoreTypesOption) {
    ParseReport report;
    ParseParams params;
    params.buildings.ignore_types = {"house"};
    const Scene scene = parse_fixture("courtyard_multipolygon", report, params);
    EXPECT_EQ(scene.buildings.size(), 1u);
    EXPECT_TRUE(find(scene, OsmType::Way, 103).empty());
}

TEST(BuildBuildings, SeedChangesOnlyRandomHeights) {
    ParseReport report;
    ParseParams other;
    other.seed = other.buildings.seed = 12345;
    const Scene a = parse_fixture("courtyard_multipolygon", report);
    const Scene b = parse_fixture("courtyard_multipolygon", report, other);
    ASSERT_EQ(a.buildings.size(), b.buildings.size());
    for (size_t i = 0; i < a.buildings.size(); ++i) {
        EXPECT_EQ(a.buildings[i].outer, b.buildings[i].outer);
        if (a.buildings[i].height_source == HeightSource::Random)
            EXPECT_NE(a.buildings[i].height, b.buildings[i].height);
        else
            EXPECT_EQ(a.buildings[i].height, b.buildings[i].height);
    }
}
