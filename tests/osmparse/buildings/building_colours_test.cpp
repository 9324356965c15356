// Colours, materials and heights where the map has none (facade styles: tests/render/facade/,
// how render draws the looks: tests/render/facade/building_looks_test.cpp).
#include <gtest/gtest.h>

#include <set>

#include "osmparse/buildings/building_colours.h"
#include "osmparse/buildings/infer_heights.h"
#include "osmparse/buildings/parse_colour.h"
#include "osmparse/pipeline.h"
#include "tests/osmparse/parse_quietly.h"
#include "tests/test_support.h"

using namespace citygen;
using citygen::test::parse_quietly;
using citygen::test::source_path;

TEST(ParseColour, NamesAndHexAndGarbage) {
    uint32_t c = 0;
    EXPECT_TRUE(parse_colour("#c84", &c));
    EXPECT_EQ(c, 0xcc8844u);
    EXPECT_TRUE(parse_colour("#A0b1C2", &c));
    EXPECT_EQ(c, 0xa0b1c2u);
    EXPECT_TRUE(parse_colour("DarkSlateGrey", &c));
    EXPECT_EQ(c, 0x2f4f4fu);
    EXPECT_TRUE(parse_colour("light grey", &c));
    EXPECT_EQ(c, 0xd3d3d3u);
    EXPECT_FALSE(parse_colour("blurple", &c));
    EXPECT_FALSE(parse_colour("#12345", &c));
    EXPECT_FALSE(parse_colour("#gggggg", &c));
    EXPECT_FALSE(parse_colour("red;blue", &c));
    EXPECT_FALSE(parse_colour("", &c));
}

TEST(BuildingColours, TaggedDefaultAndGarbageCounted) {
    ParseReport report;
    const Scene scene = parse_quietly(source_path("tests/data/roofs.osm"), report);
    EXPECT_EQ(report.note_count(ReportKind::ColoursAndMaterials, ReportReason::BadWallColour), 1);
    EXPECT_EQ(report.note_count(ReportKind::ColoursAndMaterials, ReportReason::BadRoofColour), 1);
    bool tagged_seen = false;
    for (const Building& b : scene.buildings) {
        EXPECT_NE(b.wall_colour, 0u);
        EXPECT_NE(b.roof_colour, 0u);
        if ((b.wall_colour & 0xffffff) == 0xcc8844) {
            tagged_seen = true;
            EXPECT_EQ(b.colour_inferred, 0);
            EXPECT_EQ(b.roof_colour & 0xffffff, 0x2f4f4fu);
            EXPECT_EQ(b.wall_material, WallMaterial::Brick);
            EXPECT_EQ(b.roof_material, RoofMaterial::Slate);
        }
    }
    EXPECT_TRUE(tagged_seen);
    // Untagged houses of the same type do not all get one colour.
    std::set<uint32_t> colours;
    for (const Building& b : scene.buildings)
        if (b.colour_inferred & kWallColourInferred) colours.insert(b.wall_colour);
    EXPECT_GE(colours.size(), 5u);
}

TEST(InferHeights, RulesInOrder) {
    bool sure = false;
    EXPECT_DOUBLE_EQ(height_by_type_and_area("garage", 18, &sure), 3);
    EXPECT_TRUE(sure);
    EXPECT_DOUBLE_EQ(height_by_type_and_area("yes", 20, &sure), 3);  // tiny footprint: a shed
    EXPECT_TRUE(sure);
    EXPECT_DOUBLE_EQ(height_by_type_and_area("house", 120, &sure), 8);
    EXPECT_TRUE(sure);
    EXPECT_GT(height_by_type_and_area("apartments", 400, &sure), 10);
    EXPECT_FALSE(sure);
    EXPECT_GT(height_by_type_and_area("yes", 2000, &sure), height_by_type_and_area("yes", 100, &sure));
    EXPECT_DOUBLE_EQ(height_by_type_and_area("spaceport", 400, &sure), 0);  // unknown: no rule

    auto square = [](double x, double y, double s) { return Ring{{x, y}, {x + s, y}, {x + s, y + s}, {x, y + s}}; };
    auto building = [&](int64_t id, double x, const std::string& type, double height, HeightSource source) {
        Building b;
        b.osm = {OsmType::Way, id};
        b.outer = square(x, 0, 15);
        b.type = type;
        b.height = height;
        b.height_source = source;
        return b;
    };
    BuildingParams params;
    std::vector<Building> v{building(1, 0, "apartments", 30, HeightSource::Tagged),
                            building(2, 20, "apartments", 33, HeightSource::Levels),
                            building(3, 40, "apartments", 12, HeightSource::Random),   // neighbours
                            building(4, 60, "garage", 12, HeightSource::Random),       // type beats neighbours
                            building(5, 5000, "spaceport", 12, HeightSource::Random),  // nothing applies
                            building(6, 9000, "apartments", 12, HeightSource::Random)};  // type alone
    ParseReport report;
    infer_heights(v, {}, params, report);
    EXPECT_EQ(v[0].height_rule, HeightRule::Tagged);
    EXPECT_EQ(v[1].height_rule, HeightRule::Levels);
    EXPECT_EQ(v[2].height_rule, HeightRule::Neighbours);
    EXPECT_GE(v[2].height, 0.9 * 30 - 1e-9);  // a neighbour's height, jittered by at most 10%
    EXPECT_LE(v[2].height, 1.1 * 33 + 1e-9);
    EXPECT_EQ(v[3].height_rule, HeightRule::TypeAndArea);
    EXPECT_LE(v[3].height, 3.3);
    EXPECT_EQ(v[4].height_rule, HeightRule::Random);
    EXPECT_DOUBLE_EQ(v[4].height, 12);  // the seeded random height stays
    EXPECT_EQ(v[5].height_rule, HeightRule::TypeAndArea);
    EXPECT_EQ(v[2].height_source, HeightSource::Random);  // still not from the map
}
