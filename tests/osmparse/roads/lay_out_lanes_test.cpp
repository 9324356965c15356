// Lanes and markings: the lane layout from tags, width from lanes and their extras, zebra
// crossings and stop lines placed on their road (the painted pattern render evaluates from
// them: tests/render/geometry/road_markings_test.cpp).
#include <gtest/gtest.h>

#include "osmparse/pipeline.h"
#include "osmparse/roads/build_road_graph.h"
#include "osmparse/roads/lay_out_lanes.h"
#include "tests/osmparse/parse_quietly.h"
#include "tests/test_scenes.h"

using namespace citygen;
using citygen::test::parse_quietly;
using citygen::test::road_of_way;

namespace {

OsmTags tags(std::vector<std::pair<std::string, std::string>> entries) {
    OsmTags t;
    t.entries = std::move(entries);
    return t;
}


}  // namespace

TEST(LaneLayout, FromTagsAndDefaults) {
    LaneLayout l = lane_layout(tags({{"lanes", "4"}}), RoadClass::Primary, 12, nullptr);
    EXPECT_EQ(l.forward, 2);
    EXPECT_EQ(l.backward, 2);
    EXPECT_EQ(l.centre, CentreLine::Double);
    EXPECT_TRUE(l.edge_lines);
    l = lane_layout(tags({{"lanes", "3"}, {"lanes:forward", "2"}}), RoadClass::Secondary, 9, nullptr);
    EXPECT_EQ(l.forward, 2);
    EXPECT_EQ(l.backward, 1);
    EXPECT_EQ(l.centre, CentreLine::Solid);
    l = lane_layout(tags({{"oneway", "yes"}, {"turn:lanes", "left|through|right"}}), RoadClass::Tertiary, 9, nullptr);
    EXPECT_EQ(l.forward, 3);
    EXPECT_EQ(l.backward, 0);
    EXPECT_EQ(l.centre, CentreLine::None);
    l = lane_layout(tags({{"oneway", "-1"}}), RoadClass::Residential, 4, nullptr);
    EXPECT_EQ(l.forward, 0);
    EXPECT_EQ(l.backward, 1);
    l = lane_layout(tags({}), RoadClass::Residential, 6, nullptr);
    EXPECT_EQ(l.centre, CentreLine::Dashed);
    EXPECT_FALSE(l.edge_lines);
    l = lane_layout(tags({}), RoadClass::Service, 3.5, nullptr);
    EXPECT_EQ(l.forward + l.backward, 1);
    EXPECT_EQ(l.centre, CentreLine::None);
    ParseReport report;
    l = lane_layout(tags({{"lanes", "banana"}}), RoadClass::Residential, 6, &report);
    EXPECT_EQ(l.forward + l.backward, 2);
    EXPECT_EQ(report.note_count(ReportKind::RoadLanes, ReportReason::LaneCountUnusable), 1);
}

TEST(LaneLayout, CycleBusAndParkingLanesWidenAnUntaggedRoad) {
    EXPECT_DOUBLE_EQ(lane_extras_width(tags({})), 0);
    EXPECT_DOUBLE_EQ(lane_extras_width(tags({{"cycleway", "lane"}})), 3.0);
    EXPECT_DOUBLE_EQ(lane_extras_width(tags({{"cycleway:right", "lane"}})), 1.5);
    EXPECT_DOUBLE_EQ(lane_extras_width(tags({{"parking:lane:both", "parallel"}})), 4.0);
    EXPECT_DOUBLE_EQ(lane_extras_width(tags({{"busway:left", "lane"}})), 3.0);
    RoadParams params;
    EXPECT_DOUBLE_EQ(road_width(tags({{"highway", "primary"}, {"lanes", "4"}, {"cycleway", "lane"}}), params, nullptr),
                     15.0);
    EXPECT_DOUBLE_EQ(road_width(tags({{"highway", "primary"}, {"width", "10"}, {"cycleway", "lane"}}), params, nullptr),
                     10.0);  // a tagged width already holds them
}

TEST(Markings, FixtureHasLanesAZebraAndAStopLine) {
    ParseReport report;
    const Scene s = parse_quietly(std::string(CITYGEN_SOURCE_DIR) + "/tests/data/map_lanes.osm", report);
    const RoadEdge* primary = road_of_way(s, 10);
    ASSERT_NE(primary, nullptr);
    EXPECT_DOUBLE_EQ(primary->width, 15.0);
    EXPECT_EQ(primary->lanes_forward, 2);
    EXPECT_EQ(primary->centre_line, CentreLine::Double);
    EXPECT_TRUE(primary->cycle_lane_left && primary->cycle_lane_right);  // cycleway=lane
    ASSERT_EQ(s.crossings.size(), 2u);  // the unmarked crossing is not painted
    const Crossing* zebra = nullptr;
    const Crossing* stop = nullptr;
    for (const Crossing& c : s.crossings) (c.kind == CrossingKind::Zebra ? zebra : stop) = &c;
    ASSERT_TRUE(zebra && stop);
    EXPECT_EQ(s.roads[zebra->road].osm.id, 12);
    EXPECT_EQ(s.roads[stop->road].osm.id, 10);
    EXPECT_EQ(stop->side, RoadSide::Right);  // towards the junction at the road's `to` end
    EXPECT_EQ(report.note_count(ReportKind::RoadLanes, ReportReason::LaneCountUnusable), 1);

}
