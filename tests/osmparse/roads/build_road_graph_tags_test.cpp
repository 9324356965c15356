// Road tags: class, exclusion, width rules and sidewalk sides.
#include <gtest/gtest.h>

#include "osmparse/roads/build_road_graph.h"

using namespace citygen;

namespace {
OsmTags tags(std::vector<std::pair<std::string, std::string>> kv) { return OsmTags{std::move(kv)}; }
}  // namespace

TEST(RoadTags, WidthTagWinsWithUnits) {
    RoadParams p;
    EXPECT_DOUBLE_EQ(road_width(tags({{"highway", "residential"}, {"width", "7.5"}}), p, nullptr), 7.5);
    EXPECT_DOUBLE_EQ(road_width(tags({{"highway", "residential"}, {"width", "8 m"}, {"lanes", "4"}}), p, nullptr), 8);
    EXPECT_NEAR(road_width(tags({{"highway", "residential"}, {"width", "20 ft"}}), p, nullptr), 6.096, 1e-9);
    EXPECT_DOUBLE_EQ(road_width(tags({{"highway", "residential"}, {"width", "6,5"}}), p, nullptr), 6.5);
}

TEST(RoadTags, LanesTimesLaneWidthThenClassDefault) {
    RoadParams p;
    p.lane_width = 3.25;
    EXPECT_DOUBLE_EQ(road_width(tags({{"highway", "primary"}, {"lanes", "3"}}), p, nullptr), 9.75);
    EXPECT_DOUBLE_EQ(road_width(tags({{"highway", "primary"}}), p, nullptr), default_road_width("primary", false));
    EXPECT_DOUBLE_EQ(road_width(tags({{"highway", "service"}}), p, nullptr), default_road_width("service", false));
    EXPECT_GT(default_road_width("motorway", false), default_road_width("residential", false));
    EXPECT_GT(default_road_width("residential", false), default_road_width("service", false));
}

TEST(RoadTags, AbsurdValuesFallBackAndAreCounted) {
    RoadParams p;
    ParseReport report;
    // Absurd width falls back to lanes, absurd lanes fall back to the class table.
    EXPECT_DOUBLE_EQ(road_width(tags({{"highway", "tertiary"}, {"width", "500"}, {"lanes", "2"}}), p, &report), 6);
    EXPECT_DOUBLE_EQ(road_width(tags({{"highway", "tertiary"}, {"width", "wide"}, {"lanes", "40"}}), p, &report),
                     default_road_width("tertiary", false));
    EXPECT_DOUBLE_EQ(road_width(tags({{"highway", "tertiary"}, {"width", "0.2"}}), p, &report),
                     default_road_width("tertiary", false));
    EXPECT_DOUBLE_EQ(road_width(tags({{"highway", "tertiary"}, {"width", "3;4"}}), p, &report),
                     default_road_width("tertiary", false));
    EXPECT_EQ(report.note_count(ReportKind::RoadEdges, ReportReason::WidthTagUnusable), 4);
    EXPECT_EQ(report.note_count(ReportKind::RoadEdges, ReportReason::LanesTagUnusable), 1);
}

TEST(RoadTags, WhichWaysAreCarriageways) {
    RoadParams p;
    EXPECT_FALSE(carriageway_exclusion(tags({{"highway", "residential"}}), p));
    EXPECT_FALSE(carriageway_exclusion(tags({{"highway", "primary"}, {"bridge", "yes"}}), p));
    EXPECT_TRUE(carriageway_exclusion(tags({{"highway", "footway"}}), p));
    EXPECT_TRUE(carriageway_exclusion(tags({{"highway", "steps"}}), p));
    EXPECT_TRUE(carriageway_exclusion(tags({{"highway", "cycleway"}}), p));
    EXPECT_TRUE(carriageway_exclusion(tags({{"highway", "path"}}), p));
    EXPECT_EQ(*carriageway_exclusion(tags({{"highway", "pedestrian"}, {"area", "yes"}}), p),
              ReportReason::NotACarriagewayClass);
    EXPECT_EQ(*carriageway_exclusion(tags({{"highway", "service"}, {"area", "yes"}}), p), ReportReason::AreaYes);
    EXPECT_EQ(*carriageway_exclusion(tags({{"highway", "primary"}, {"tunnel", "yes"}}), p), ReportReason::Tunnel);
    EXPECT_FALSE(carriageway_exclusion(tags({{"highway", "primary"}, {"tunnel", "no"}}), p));
    p.classes = {"primary"};
    EXPECT_TRUE(carriageway_exclusion(tags({{"highway", "residential"}}), p));
}

TEST(RoadTags, OneWayRoadsDefaultNarrower) {
    RoadParams p;
    EXPECT_DOUBLE_EQ(road_width(tags({{"highway", "residential"}, {"oneway", "yes"}}), p, nullptr),
                     default_road_width("residential", true));
    EXPECT_LT(default_road_width("residential", true), default_road_width("residential", false));
    EXPECT_DOUBLE_EQ(road_width(tags({{"highway", "tertiary"}, {"junction", "roundabout"}}), p, nullptr),
                     default_road_width("tertiary", true));
    EXPECT_DOUBLE_EQ(road_width(tags({{"highway", "tertiary"}, {"junction", "roundabout"}, {"oneway", "no"}}), p, nullptr),
                     default_road_width("tertiary", false));
    // Tags still win over the table.
    EXPECT_DOUBLE_EQ(road_width(tags({{"highway", "residential"}, {"oneway", "yes"}, {"lanes", "2"}}), p, nullptr), 6);
    EXPECT_TRUE(is_oneway(tags({{"highway", "primary"}, {"oneway", "-1"}})));
    EXPECT_TRUE(is_oneway(tags({{"highway", "motorway"}})));
    EXPECT_FALSE(is_oneway(tags({{"highway", "motorway"}, {"oneway", "no"}})));
    EXPECT_FALSE(is_oneway(tags({{"highway", "primary"}})));
}

TEST(RoadTags, ClassMapping) {
    EXPECT_EQ(road_class_of("motorway_link"), RoadClass::Motorway);
    EXPECT_EQ(road_class_of("primary"), RoadClass::Primary);
    EXPECT_EQ(road_class_of("living_street"), RoadClass::LivingStreet);
    EXPECT_EQ(road_class_of("service"), RoadClass::Service);
    EXPECT_EQ(road_class_of("bus_guideway"), RoadClass::Other);
}

TEST(RoadTags, SidewalkSides) {
    auto sides = [](std::vector<std::pair<std::string, std::string>> kv) {
        const SidewalkSides s = sidewalk_sides(tags(std::move(kv)));
        return std::make_pair(s.left, s.right);
    };
    using P = std::pair<bool, bool>;
    EXPECT_EQ(sides({{"highway", "service"}, {"sidewalk", "both"}}), P(true, true));
    EXPECT_EQ(sides({{"highway", "residential"}, {"sidewalk", "left"}}), P(true, false));
    EXPECT_EQ(sides({{"highway", "residential"}, {"sidewalk", "right"}}), P(false, true));
    EXPECT_EQ(sides({{"highway", "residential"}, {"sidewalk", "no"}}), P(false, false));
    EXPECT_EQ(sides({{"highway", "residential"}, {"sidewalk", "separate"}}), P(false, false));
    EXPECT_EQ(sides({{"highway", "residential"}, {"sidewalk:left", "yes"}, {"sidewalk:right", "separate"}}),
              P(true, false));
    EXPECT_EQ(sides({{"highway", "residential"}, {"sidewalk:both", "yes"}}), P(true, true));
    // Untagged: by class.
    EXPECT_EQ(sides({{"highway", "residential"}}), P(true, true));
    EXPECT_EQ(sides({{"highway", "tertiary"}}), P(true, true));
    EXPECT_EQ(sides({{"highway", "motorway"}}), P(false, false));
    EXPECT_EQ(sides({{"highway", "service"}}), P(false, false));
}
