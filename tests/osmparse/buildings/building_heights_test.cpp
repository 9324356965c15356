#include <gtest/gtest.h>

#include "osmparse/buildings/building_heights.h"

using namespace citygen;

namespace {

OsmTags tags(std::initializer_list<std::pair<std::string, std::string>> entries) {
    OsmTags t;
    for (const auto& e : entries) t.entries.push_back(e);
    return t;
}

BuildingHeight height_of(const OsmTags& t, ParseReport& report, int64_t id = 7,
                         BuildingParams params = BuildingParams{}) {
    return building_height(t, {OsmType::Way, id}, params, report, ReportKind::Buildings);
}

}  // namespace

TEST(BuildingHeights, TaggedHeightWithUnits) {
    ParseReport report;
    BuildingHeight h = height_of(tags({{"building", "yes"}, {"height", "40 ft"}}), report);
    EXPECT_NEAR(h.height, 12.192, 1e-9);
    EXPECT_EQ(h.source, HeightSource::Tagged);
    EXPECT_EQ(h.min_height, 0);
    EXPECT_EQ(h.levels, 4);  // 12.2 m / 3 m per level
    h = height_of(tags({{"height", "12'6\""}, {"min_height", "10'"}}), report);
    EXPECT_NEAR(h.height, 3.81, 1e-9);
    EXPECT_NEAR(h.min_height, 3.048, 1e-9);
    EXPECT_EQ(report.note_count(ReportKind::Buildings, ReportReason::HeightFromHeightTag), 2);
}

TEST(BuildingHeights, LevelsTimesLevelHeight) {
    ParseReport report;
    BuildingHeight h = height_of(tags({{"building:levels", "5"}, {"building:min_level", "2"}}), report);
    EXPECT_DOUBLE_EQ(h.height, 15);
    EXPECT_DOUBLE_EQ(h.min_height, 6);
    EXPECT_EQ(h.levels, 3);
    EXPECT_EQ(h.source, HeightSource::Levels);
    BuildingParams tall_levels;
    tall_levels.level_height = 4;
    h = height_of(tags({{"building:levels", "5"}, {"roof:levels", "2"}}), report, 7, tall_levels);
    EXPECT_DOUBLE_EQ(h.height, 20);  // roof levels are ignored
}

TEST(BuildingHeights, HeightTagWinsOverLevels) {
    ParseReport report;
    BuildingHeight h = height_of(tags({{"height", "22"}, {"building:levels", "3"}}), report);
    EXPECT_DOUBLE_EQ(h.height, 22);
    EXPECT_EQ(h.levels, 3);
    EXPECT_EQ(h.source, HeightSource::Tagged);
}

TEST(BuildingHeights, RandomOnlyWhenNothingTaggedAndIndependentOfOrder) {
    ParseReport report;
    BuildingParams params;
    params.seed = 42;
    const BuildingHeight a = height_of(tags({{"building", "yes"}}), report, 1001, params);
    const BuildingHeight b = height_of(tags({{"building", "house"}}), report, 1002, params);
    const BuildingHeight a_again = height_of(tags({{"building", "yes"}}), report, 1001, params);
    EXPECT_EQ(a.source, HeightSource::Random);
    EXPECT_GE(a.height, params.random_min_height);
    EXPECT_LE(a.height, params.random_max_height);
    EXPECT_EQ(a.height, a_again.height);
    EXPECT_NE(a.height, b.height);
    params.seed = 43;
    EXPECT_NE(height_of(tags({{"building", "yes"}}), report, 1001, params).height, a.height);
    EXPECT_EQ(report.note_count(ReportKind::Buildings, ReportReason::RandomHeight), 4);
}

TEST(BuildingHeights, RandomHeightsSpanTheRange) {
    ParseReport report;
    BuildingParams params;
    double lowest = 1e9, highest = -1e9;
    for (int64_t id = 1; id <= 2000; ++id) {
        const double h = height_of(tags({}), report, id, params).height;
        ASSERT_GE(h, params.random_min_height);
        ASSERT_LE(h, params.random_max_height);
        lowest = std::min(lowest, h);
        highest = std::max(highest, h);
    }
    EXPECT_LT(lowest, params.random_min_height + 0.5);
    EXPECT_GT(highest, params.random_max_height - 0.5);
}

TEST(BuildingHeights, AbsurdOrUnparseableValuesFallBackAndAreCounted) {
    ParseReport report;
    BuildingHeight h = height_of(tags({{"height", "-5"}, {"building:levels", "4"}}), report);
    EXPECT_EQ(h.source, HeightSource::Levels);
    EXPECT_DOUBLE_EQ(h.height, 12);
    h = height_of(tags({{"height", "2000"}}), report);
    EXPECT_EQ(h.source, HeightSource::Random);
    h = height_of(tags({{"height", "tall"}, {"building:levels", "many"}}), report);
    EXPECT_EQ(h.source, HeightSource::Random);
    h = height_of(tags({{"building:levels", "500"}}), report);  // 1500 m
    EXPECT_EQ(h.source, HeightSource::Random);
    EXPECT_EQ(report.note_count(ReportKind::Buildings, ReportReason::BadHeightTag), 3);
    EXPECT_EQ(report.note_count(ReportKind::Buildings, ReportReason::BadLevelsTag), 2);
}

TEST(BuildingHeights, MinHeightNotBelowHeightIsIgnored) {
    ParseReport report;
    BuildingHeight h = height_of(tags({{"height", "10"}, {"min_height", "12"}}), report);
    EXPECT_DOUBLE_EQ(h.height, 10);
    EXPECT_DOUBLE_EQ(h.min_height, 0);
    EXPECT_EQ(report.note_count(ReportKind::Buildings, ReportReason::MinHeightNotBelowHeight), 1);
}

TEST(BuildingHeights, OnlyMinHeightTaggedGivesOneStoreyAboveIt) {
    ParseReport report;
    BuildingParams params;
    const BuildingHeight h = height_of(tags({{"building:part", "yes"}, {"min_height", "45"}}), report, 9, params);
    EXPECT_DOUBLE_EQ(h.min_height, 45);
    EXPECT_DOUBLE_EQ(h.height, 45 + params.level_height);
    EXPECT_EQ(h.levels, 1);
}
