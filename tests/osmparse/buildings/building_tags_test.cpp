// BuildingTagIndex: the tags roofs and colours read, found by the building's OSM identity.
#include <gtest/gtest.h>

#include "osmparse/buildings/building_tags.h"

using namespace citygen;

namespace {

OsmArea area(int64_t id, std::vector<std::pair<std::string, std::string>> tags) {
    OsmArea a;
    a.ref = {OsmType::Way, id};
    a.tags.entries = std::move(tags);
    return a;
}

}  // namespace

TEST(BuildingTags, KeepsRoofAndBuildingKeysOfTheFirstAreaOfARef) {
    std::vector<OsmArea> areas = {
        area(7, {{"building", "house"}, {"roof:shape", "gabled"}, {"building:colour", "red"}, {"name", "A"}}),
        area(3, {{"building", "yes"}, {"source", "survey"}}),  // nothing roofs or colours read
        area(7, {{"roof:shape", "flat"}}),                     // a second area of way 7: not found
    };
    const BuildingTagIndex index(std::move(areas));
    EXPECT_TRUE(areas.empty()) << "the areas are freed";
    const OsmTags& seven = index.find({OsmType::Way, 7});
    EXPECT_STREQ(seven.get("roof:shape"), "gabled");
    EXPECT_STREQ(seven.get("building:colour"), "red");
    EXPECT_EQ(seven.get("name"), nullptr);
    EXPECT_EQ(seven.get("building"), nullptr);
    EXPECT_TRUE(index.find({OsmType::Way, 3}).entries.empty());
    EXPECT_TRUE(index.find({OsmType::Relation, 7}).entries.empty());
}

TEST(BuildingTags, CopyFromOsmDataFindsTheSame) {
    OsmData osm;
    osm.building_areas = {area(5, {{"roof:colour", "#aa0000"}, {"height", "12"}})};
    const BuildingTagIndex index(osm);
    EXPECT_EQ(osm.building_areas.size(), 1u) << "the const constructor copies";
    EXPECT_STREQ(index.find({OsmType::Way, 5}).get("roof:colour"), "#aa0000");
    EXPECT_EQ(index.find({OsmType::Way, 5}).get("height"), nullptr);
}
