// Heights where the map has none (osmparse/buildings/infer_heights.h): each rule decides where it should
// and says so in height_rule, hidden tags never leak, the result does not depend on order.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>

#include "osmparse/buildings/infer_heights.h"
#include "osmparse/pipeline.h"

namespace citygen {
namespace {

Ring square(double x, double y, double side) { return {{x, y}, {x + side, y}, {x + side, y + side}, {x, y + side}}; }

Building building(int64_t id, double x, double y, const std::string& type, double height, HeightSource source,
                  double side = 15) {
    Building b;
    b.osm = {OsmType::Way, id};
    b.outer = square(x, y, side);
    b.type = type;
    b.height = height;
    b.height_source = source;
    return b;
}

const Building& by_id(const std::vector<Building>& v, int64_t id) {
    return *std::find_if(v.begin(), v.end(), [&](const Building& b) { return b.osm.id == id; });
}

// The jitter is at most 10% either way.
void expect_near_guess(const Building& b, double guess) {
    EXPECT_GE(b.height, 0.9 * guess - 1e-9) << b.osm.id;
    EXPECT_LE(b.height, 1.1 * guess + 1e-9) << b.osm.id;
}

TEST(InferHeights, TaggedNeighboursOfTheSameKindDecide) {
    BuildingParams params;
    std::vector<Building> v{building(1, 0, 0, "yes", 21, HeightSource::Tagged),
                            building(2, 20, 0, "yes", 24, HeightSource::Levels),
                            building(3, 40, 0, "yes", 27, HeightSource::Tagged),
                            // A tower of another size next door says nothing about it.
                            building(4, 0, 20, "yes", 120, HeightSource::Tagged, 60),
                            building(5, 20, 20, "yes", 12, HeightSource::Random)};
    ParseReport report;
    infer_heights(v, {}, params, report);
    const Building& b = by_id(v, 5);
    EXPECT_EQ(b.height_rule, HeightRule::Neighbours);
    EXPECT_EQ(b.height_source, HeightSource::Random) << "still not from the map";
    expect_near_guess(b, 24);  // the weighted median of 21, 24 and 27
    EXPECT_EQ(by_id(v, 1).height_rule, HeightRule::Tagged);
    EXPECT_EQ(by_id(v, 2).height_rule, HeightRule::Levels);

    // Only one like it: all three tagged near count, and they agree (15, 21, 24 m).
    v.erase(v.begin() + 2);
    v.erase(v.begin() + 1);
    v.push_back(building(6, 40, 0, "office", 15, HeightSource::Tagged));
    v.push_back(building(7, 40, 20, "school", 24, HeightSource::Tagged));
    const Building tower = by_id(v, 4);
    v.erase(std::find_if(v.begin(), v.end(), [](const Building& b) { return b.osm.id == 4; }));
    infer_heights(v, {}, params, report);
    EXPECT_EQ(by_id(v, 5).height_rule, HeightRule::Neighbours);
    expect_near_guess(by_id(v, 5), 21);  // the weighted median of 15, 21 and 24

    // With the tower instead of the school they disagree (15, 21, 120 m: houses beside a
    // tower say nothing about one more building): the footprint rule decides.
    v.pop_back();
    v.push_back(tower);
    infer_heights(v, {}, params, report);
    EXPECT_EQ(by_id(v, 5).height_rule, HeightRule::TypeAndArea);
    // (The tower's footprint reaches its wall.)
    expect_near_guess(by_id(v, 5), params.level_height * levels_from_surroundings(225, 225, true));
}

TEST(InferHeights, NeighboursThatDisagreeStillBeatARandomHeight) {
    BuildingParams params;
    // A type no table knows, among tagged buildings of 6, 9 and 60 m (20 m away each).
    std::vector<Building> v{building(1, 20, 0, "yes", 6, HeightSource::Tagged),
                            building(2, -20, 0, "yes", 9, HeightSource::Tagged),
                            building(3, 0, 20, "yes", 60, HeightSource::Tagged),
                            building(4, 0, 0, "ice_rink", 30, HeightSource::Random)};
    ParseReport report;
    infer_heights(v, {}, params, report);
    EXPECT_EQ(by_id(v, 4).height_rule, HeightRule::Neighbours);
    expect_near_guess(by_id(v, 4), 9);
    EXPECT_EQ(report.note_count(ReportKind::BuildingHeights, ReportReason::FromDisagreeingNeighbours), 1);
}

TEST(InferHeights, SameTypeNeighboursBeatOtherTypes) {
    BuildingParams params;
    std::vector<Building> v{building(1, 0, 0, "apartments", 45, HeightSource::Tagged),
                            building(2, 20, 0, "apartments", 45, HeightSource::Tagged),
                            building(7, 60, 0, "apartments", 48, HeightSource::Tagged),
                            building(3, 0, 20, "office", 9, HeightSource::Tagged),
                            building(4, 20, 20, "office", 9, HeightSource::Tagged),
                            building(5, 40, 20, "office", 9, HeightSource::Tagged),
                            building(6, 40, 0, "apartments", 12, HeightSource::Random)};
    ParseReport report;
    infer_heights(v, {}, params, report);
    EXPECT_EQ(by_id(v, 6).height_rule, HeightRule::Neighbours);
    expect_near_guess(by_id(v, 6), 45);
}

TEST(InferHeights, HiddenTruthIsNeverANeighbour) {
    // Buildings whose height is a guess (their tags hidden or absent) carry a height, but it must
    // never feed a rule: here they "know" 90 m, the tagged ones say 12 m.
    BuildingParams params;
    std::vector<Building> v;
    for (int i = 0; i < 6; ++i) v.push_back(building(10 + i, 20.0 * i, 0, "yes", 90, HeightSource::Random));
    for (int i = 0; i < 3; ++i) v.push_back(building(20 + i, 20.0 * i, 20, "yes", 12, HeightSource::Tagged));
    ParseReport report;
    infer_heights(v, {}, params, report);
    for (int i = 0; i < 6; ++i) {
        EXPECT_EQ(by_id(v, 10 + i).height_rule, HeightRule::Neighbours);
        expect_near_guess(by_id(v, 10 + i), 12);
    }
}

TEST(InferHeights, ExtractWideMedianOfTheSameKindWhenNoneIsNear) {
    BuildingParams params;
    // Ten tagged `yes` buildings of its size far apart (none within 150 m of another), three
    // dormitories: too few for a rule.
    std::vector<Building> v;
    for (int i = 0; i < 10; ++i) v.push_back(building(100 + i, 1000.0 * i, 0, "yes", 12.0 + 2 * i, HeightSource::Tagged));
    for (int i = 0; i < 3; ++i) v.push_back(building(200 + i, 1000.0 * i, 3000, "dormitory", 60, HeightSource::Tagged));
    v.push_back(building(4, 5000, 5000, "yes", 5, HeightSource::Random));
    v.push_back(building(5, 9000, 9000, "dormitory", 5, HeightSource::Random));
    ParseReport report;
    infer_heights(v, {}, params, report);
    EXPECT_EQ(by_id(v, 4).height_rule, HeightRule::Neighbours);
    expect_near_guess(by_id(v, 4), 21);  // the median of 12, 14, ..., 30
    EXPECT_EQ(by_id(v, 5).height_rule, HeightRule::TypeAndArea);
    // Too few tagged dormitories: a home takes the type table.
    bool sure = false;
    expect_near_guess(by_id(v, 5), height_by_type_and_area("dormitory", 225, &sure));
    EXPECT_EQ(report.note_count(ReportKind::BuildingHeights, ReportReason::FromExtractMedian), 1);
}

TEST(InferHeights, UntypedHallsOnIndustrialLand) {
    BuildingParams params;
    LandUseArea industrial;
    industrial.outer = square(-100, -100, 200);
    industrial.use = LandUse::Industrial;
    std::vector<Building> v{building(1, 0, 0, "yes", 30, HeightSource::Random, 25),      // 625 m2, inside
                            building(2, 1000, 0, "yes", 30, HeightSource::Random, 25),   // outside
                            building(3, 10, 10, "house", 30, HeightSource::Random, 10)};  // typed: type wins
    ParseReport report;
    infer_heights(v, {industrial}, params, report);
    bool sure = false;
    EXPECT_EQ(by_id(v, 1).height_rule, HeightRule::TypeAndArea);
    expect_near_guess(by_id(v, 1), height_by_type_and_area("industrial", 625, &sure));
    expect_near_guess(by_id(v, 2), params.level_height * levels_from_surroundings(625, 625, false));
    EXPECT_LT(height_by_type_and_area("yes", 625, &sure, LandUse::Industrial), height_by_type_and_area("yes", 625, &sure));
    expect_near_guess(by_id(v, 3), 8);
}

TEST(InferHeights, StoreysFromSurroundingsFollowFabricFootprintAndWalls) {
    // A coarser fabric is built higher, a larger footprint within it too.
    EXPECT_LT(levels_from_surroundings(300, 100, false), levels_from_surroundings(300, 400, false));
    EXPECT_LT(levels_from_surroundings(150, 200, false), levels_from_surroundings(1500, 200, false));
    // A shared wall adds height: a closed block or a terrace.
    EXPECT_GT(levels_from_surroundings(200, 200, true), 1.2 * levels_from_surroundings(200, 200, false));
    // A house among houses: one or two storeys; a shed: one.
    const double house = levels_from_surroundings(120, 120, false);
    EXPECT_GE(house, 1.5);
    EXPECT_LE(house, 2.5);
    EXPECT_EQ(levels_from_surroundings(20, 50, false), 1);
    // A fabric coarser than a city of blocks is an estate of halls, not a taller city; a
    // footprint far beyond its fabric's is a hall or a complex.
    EXPECT_EQ(levels_from_surroundings(300, 5000, false), levels_from_surroundings(300, 500, false));
    EXPECT_EQ(levels_from_surroundings(50000, 500, false), levels_from_surroundings(5000, 500, false));
}

// n x n buildings of `side` metres on a grid of `pitch` metres, ids from `first`.
void add_field(std::vector<Building>& v, int64_t first, double x0, int n, double side, double pitch) {
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j)
            v.push_back(building(first + i * n + j, x0 + pitch * i, pitch * j, "yes", 10, HeightSource::Random, side));
}

TEST(InferHeights, AnUntypedHouseInAVillageStandsTwoStoreys) {
    // A detached 120 m2 building among houses of 120 m2: about two storeys (the prior is the
    // median city's: the extract's own tagged houses raise it where they stand higher).
    BuildingParams params;
    EXPECT_GE(params.level_height * levels_from_surroundings(120, 120, false), 5.0);
    EXPECT_LT(params.level_height * levels_from_surroundings(120, 120, false), 7.0);
}

TEST(InferHeights, APriorCityOfBlocksIsNotStoodTooTall) {
    // Attached blocks of 400 m2 in a fabric of 400 m2: about five storeys (16 m), the median
    // city's, not the six (17.9 m) of a prior fitted to Monaco and Kaiserslautern; a larger
    // block in it (1,200 m2) 22 m, not the 25 m of that prior.
    BuildingParams params;
    EXPECT_LT(params.level_height * levels_from_surroundings(400, 400, true), 17.0);
    EXPECT_LT(params.level_height * levels_from_surroundings(1200, 400, true), 23.0);
    EXPECT_GT(params.level_height * levels_from_surroundings(400, 400, true), 14.0);
}

// A suburb of 100 m2 houses and a town of 400 m2 blocks, 5 km apart, with the same 20 x 20 m
// building of `type` beside each, touching none: ids 1 (suburb) and 2 (town).
std::vector<Building> suburb_and_town_with(const std::string& type) {
    std::vector<Building> v;
    add_field(v, 1000, 0, 6, 10, 25);
    add_field(v, 2000, 5000, 6, 20, 40);
    v.push_back(building(1, 150, 50, type, 10, HeightSource::Random, 20));
    v.push_back(building(2, 5240, 50, type, 10, HeightSource::Random, 20));
    return v;
}

TEST(InferHeights, UntypedBuildingsTakeTheirTownsFabric) {
    BuildingParams params;
    std::vector<Building> v = suburb_and_town_with("yes");
    ParseReport report;
    infer_heights(v, {}, params, report);
    for (int64_t id : {1, 2}) EXPECT_EQ(by_id(v, id).height_rule, HeightRule::TypeAndArea);
    EXPECT_GT(by_id(v, 2).height, 1.5 * by_id(v, 1).height);
    expect_near_guess(by_id(v, 1), params.level_height * levels_from_surroundings(400, 100, false));
    expect_near_guess(by_id(v, 2), params.level_height * levels_from_surroundings(400, 400, false));
    EXPECT_EQ(report.note_count(ReportKind::BuildingHeights, ReportReason::FromSurroundings), 74);
}

TEST(InferHeights, SharedWallsAndWorkplaces) {
    BuildingParams params;
    // Two buildings wall to wall (10 cm apart: drawn by hand), one standing 5 m off.
    std::vector<Building> v{building(1, 0, 0, "yes", 10, HeightSource::Random),
                            building(2, 15.1, 0, "yes", 10, HeightSource::Random),
                            building(3, 0, 20, "yes", 10, HeightSource::Random),
                            // Workplaces (commercial, office) follow the fabric, a church its type.
                            building(4, 300, 0, "commercial", 10, HeightSource::Random),
                            building(5, 300, 100, "office", 10, HeightSource::Random),
                            building(6, 300, 200, "church", 10, HeightSource::Random)};
    ParseReport report;
    infer_heights(v, {}, params, report);
    const double grain = 225;  // every footprint is 15 x 15 m
    const double h = params.level_height;
    expect_near_guess(by_id(v, 1), h * levels_from_surroundings(225, grain, true));
    expect_near_guess(by_id(v, 2), h * levels_from_surroundings(225, grain, true));
    expect_near_guess(by_id(v, 3), h * levels_from_surroundings(225, grain, false));
    expect_near_guess(by_id(v, 4), h * levels_from_surroundings(225, grain, false));
    expect_near_guess(by_id(v, 5), h * levels_from_surroundings(225, grain, false));
    bool sure = false;
    expect_near_guess(by_id(v, 6), height_by_type_and_area("church", 225, &sure));
    EXPECT_EQ(height_by_type_and_area("supermarket", 1500, &sure), 3) << "one storey";
}

TEST(InferHeights, PointBlocksAreHomesWithADeepPlanInATownOfBlocks) {
    // A 30 x 30 m block of flats (plan depth 2 * 900 / 120 = 15 m): flats around a core.
    EXPECT_TRUE(is_point_block("apartments", 900, 120, 300));
    EXPECT_TRUE(is_point_block("residential", 900, 120, 300));
    EXPECT_TRUE(is_point_block("dormitory", 900, 120, 300));
    // A 26 x 26 m plan is the least that counts (depth 13 m), 25 x 25 m is not.
    EXPECT_TRUE(is_point_block("apartments", 676, 104, 300));
    EXPECT_FALSE(is_point_block("apartments", 625, 100, 300));
    // A slab of flats 14 m deep and 100 m long is long, not deep (depth 12.3 m).
    EXPECT_FALSE(is_point_block("apartments", 1400, 228, 300));
    // A 40 x 40 m closed block around a 24 x 24 m courtyard: its plan is a ring 8 m deep.
    EXPECT_FALSE(is_point_block("apartments", 1600 - 576, 160 + 96, 300));
    // A 45 x 45 m plan is one core's floor (2,025 m2 is over it: a block of several cores, as a
    // 66 x 66 m mansion block of 15 m is).
    EXPECT_TRUE(is_point_block("apartments", 1936, 176, 300));
    EXPECT_FALSE(is_point_block("apartments", 2025, 180, 300));
    EXPECT_FALSE(is_point_block("apartments", 4356, 264, 300));
    // Not a home: offices, halls and untyped buildings are deep without being towers.
    EXPECT_FALSE(is_point_block("yes", 900, 120, 300));
    EXPECT_FALSE(is_point_block("office", 900, 120, 300));
    // In a village of houses (grain 120 m2) a deep home is a farmstead or a care home.
    EXPECT_FALSE(is_point_block("apartments", 900, 120, 120));
    EXPECT_FALSE(is_point_block("apartments", 900, 0, 300)) << "no perimeter, no plan";
}

TEST(InferHeights, PointBlockBeatsItsTaggedNeighbours) {
    BuildingParams params;
    std::vector<Building> v;
    // A town of 15 x 15 m blocks of flats, all tagged 15 m (grain 225 m2) ...
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            v.push_back(building(100 + 4 * i + j, 25.0 * i, 25.0 * j, "apartments", 15, HeightSource::Tagged));
    // ... with a 30 x 30 m one at its edge and a 60 x 12 m slab beside, nothing tagged.
    v.push_back(building(1, 100, 0, "apartments", 10, HeightSource::Random, 30));
    Building slab = building(2, 100, 40, "apartments", 10, HeightSource::Random);
    slab.outer = {{100, 40}, {160, 40}, {160, 52}, {100, 52}};
    v.push_back(slab);
    // The same 30 x 30 m plan with a 20 x 20 m courtyard is a closed block, not a tower.
    Building court = building(3, 0, 100, "apartments", 10, HeightSource::Random, 30);
    court.holes = {{{5, 105}, {5, 125}, {25, 125}, {25, 105}}};
    v.push_back(court);
    ParseReport report;
    infer_heights(v, {}, params, report);
    EXPECT_EQ(by_id(v, 1).height_rule, HeightRule::TypeAndArea);
    expect_near_guess(by_id(v, 1), tower_height(225, params));  // every footprint but 3 is 15 x 15 m
    EXPECT_EQ(by_id(v, 2).height_rule, HeightRule::Neighbours);
    expect_near_guess(by_id(v, 2), 15);
    EXPECT_EQ(by_id(v, 3).height_rule, HeightRule::Neighbours);
    expect_near_guess(by_id(v, 3), 15);
    EXPECT_EQ(report.note_count(ReportKind::BuildingHeights, ReportReason::PointBlock), 1);
}

TEST(InferHeights, TowersStandHigherInADenserFabric) {
    BuildingParams params;
    // 15 storeys at least, in a suburb too.
    EXPECT_DOUBLE_EQ(tower_height(120, params), 15 * params.level_height);
    EXPECT_DOUBLE_EQ(tower_height(200, params), 15 * params.level_height);
    // Higher in a city of blocks, as its other buildings are: the same growth as rule 5's.
    EXPECT_NEAR(tower_height(350, params) / tower_height(200, params),
                levels_from_surroundings(350, 350, false) / levels_from_surroundings(200, 200, false), 1e-9);
    EXPECT_GT(tower_height(350, params), 20 * params.level_height);
    EXPECT_GT(tower_height(500, params), tower_height(350, params));
    // A coarser grain than 500 m2 is an estate of halls (a campus), no denser city.
    EXPECT_DOUBLE_EQ(tower_height(1200, params), 15 * params.level_height);
}

TEST(InferHeights, FlatsAreTheTablesStoreysInAnyFabric) {
    BuildingParams params;
    // The same 20 x 20 m block of flats (plan depth 10 m: no tower) in a suburb and in a town.
    std::vector<Building> v = suburb_and_town_with("apartments");
    ParseReport report;
    infer_heights(v, {}, params, report);
    bool sure = false;
    const double table = height_by_type_and_area("apartments", 400, &sure);
    expect_near_guess(by_id(v, 1), table);
    expect_near_guess(by_id(v, 2), table);
    EXPECT_NEAR(fabric_factor(400), std::pow(2.0, 0.65), 1e-9);
    EXPECT_DOUBLE_EQ(fabric_factor(1200), 1) << "an estate of halls";
    // Towers grow with the fabric alike.
    EXPECT_NEAR(tower_height(400, params) / tower_height(200, params), fabric_factor(400), 1e-9);
}

TEST(InferHeights, ATaggedTwinNextDoorDecides) {
    BuildingParams params;
    // A row of 17 x 17 m blocks of flats 28 m apart; only the first is tagged (42 m).
    std::vector<Building> v{building(1, 0, 0, "apartments", 42, HeightSource::Levels, 17),
                            building(2, 28, 0, "apartments", 10, HeightSource::Random, 17),
                            // 10% larger still is the same design; 30% larger is not.
                            building(3, 0, 28, "apartments", 10, HeightSource::Random, 17.8),
                            building(4, 28, 28, "apartments", 10, HeightSource::Random, 19.5),
                            // Too far (80 m), another type, no type.
                            building(5, 80, 0, "apartments", 10, HeightSource::Random, 17),
                            building(6, 0, -28, "office", 10, HeightSource::Random, 17),
                            building(7, 28, -28, "yes", 10, HeightSource::Random, 17)};
    v.push_back(building(8, 28, -56, "yes", 42, HeightSource::Tagged, 17));
    ParseReport report;
    infer_heights(v, {}, params, report);
    for (int64_t id : {2, 3}) {
        EXPECT_EQ(by_id(v, id).height_rule, HeightRule::Neighbours) << id;
        expect_near_guess(by_id(v, id), 42);
    }
    for (int64_t id : {4, 5, 6}) EXPECT_LT(by_id(v, id).height, 0.6 * 42) << id;
    EXPECT_LT(by_id(v, 7).height, 0.6 * 42) << "two untyped buildings of one size are no estate";
    EXPECT_EQ(report.note_count(ReportKind::BuildingHeights, ReportReason::Twin), 2);
}

// A town of 15 x 15 m untyped blocks (grain 225 m2), nothing tagged: ids 100-115.
void add_blocks(std::vector<Building>& v) {
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) v.push_back(building(100 + 4 * i + j, 25.0 * i, 25.0 * j, "yes", 10, HeightSource::Random));
}

TEST(InferHeights, UseTagsMakeAHome) {
    OsmData osm;
    auto add = [&](int64_t id, const char* form, const char* key, const char* value) {
        OsmArea a;
        a.ref = {OsmType::Way, id};
        a.tags.entries = {{"building", form}};
        if (key) a.tags.entries.push_back({key, value});
        osm.building_areas.push_back(a);
    };
    add(1, "commercial", "tourism", "apartment");       // holiday flats in a "commercial" tower
    add(2, "yes", "building:use", "residential");
    add(3, "retail", "building:use", "apartments");
    add(4, "commercial", nullptr, nullptr);
    add(5, "house", "building:use", "residential");     // a house is a home already
    add(6, "yes", "tourism", "hotel");
    add(7, "office", "building:use", "office");
    EXPECT_EQ(homes_by_use(osm), (std::set<OsmRef>{{OsmType::Way, 1}, {OsmType::Way, 2}, {OsmType::Way, 3}}));

    // In a town of blocks (grain 225 m2) a 30 x 30 m "commercial" building holding flats is a
    // point block; without its use tags it is a workplace of the fabric's height.
    BuildingParams params;
    std::vector<Building> v;
    add_blocks(v);
    v.push_back(building(1, 100, 0, "commercial", 10, HeightSource::Random, 30));
    std::vector<Building> untagged_use = v;
    ParseReport report;
    infer_heights(v, {}, params, report, {{OsmType::Way, 1}});
    expect_near_guess(by_id(v, 1), tower_height(225, params));
    EXPECT_EQ(report.note_count(ReportKind::BuildingHeights, ReportReason::PointBlock), 1);
    infer_heights(untagged_use, {}, params, report);
    EXPECT_LT(by_id(untagged_use, 1).height, 0.6 * tower_height(225, params));
}

TEST(InferHeights, AHouseTypeOnABlocksFootprintIsABlockInEveryRule) {
    BuildingParams params;
    std::vector<Building> v;
    add_blocks(v);
    // A "terrace" of 40 x 40 m (plan depth 20 m) in a town of 15 x 15 m blocks: a point block.
    v.push_back(building(1, 150, 0, "terrace", 10, HeightSource::Random, 40));
    // A row of ten 100 m2 houses (1,000 m2) is still houses.
    Building row = building(2, 0, 150, "terrace", 10, HeightSource::Random);
    row.outer = {{0, 150}, {100, 150}, {100, 160}, {0, 160}};
    v.push_back(row);
    ParseReport report;
    infer_heights(v, {}, params, report);
    expect_near_guess(by_id(v, 1), tower_height(225, params));
    expect_near_guess(by_id(v, 2), 8);
}

TEST(InferHeights, AHouseTypeOnABlocksFootprintIsABlock) {
    bool sure = false;
    EXPECT_DOUBLE_EQ(height_by_type_and_area("terrace", 600, &sure), 8);
    EXPECT_TRUE(sure) << "a row of houses";
    for (const char* type : {"terrace", "house", "detached"}) {
        EXPECT_DOUBLE_EQ(height_by_type_and_area(type, 3000, &sure), height_by_type_and_area("residential", 3000, &sure));
        EXPECT_FALSE(sure) << type << ": tagged neighbours may say more";
        EXPECT_GT(height_by_type_and_area(type, 3000, &sure), 2 * 8);
    }
}

double median_height(const std::vector<Building>& v, int64_t from, int64_t to) {
    std::vector<double> h;
    for (const Building& b : v)
        if (b.osm.id >= from && b.osm.id < to) h.push_back(b.height);
    std::sort(h.begin(), h.end());
    return h[h.size() / 2];
}

// A city of closed blocks: rows of attached 20 x 20 m blocks, `tagged` rows of them tagged five
// storeys (15 m), and far from them (no tagged neighbour) rows of untagged blocks of 700 m2,
// a footprint class none of the tagged ones is in.
std::vector<Building> city_of_blocks(int tagged_rows) {
    std::vector<Building> v;
    for (int r = 0; r < tagged_rows; ++r)
        for (int i = 0; i < 10; ++i)
            v.push_back(building(100 + 10 * r + i, 20.0 * i, 30.0 * r, "yes", 15, HeightSource::Levels, 20));
    for (int r = 0; r < 2; ++r)
        for (int i = 0; i < 8; ++i) {
            Building b = building(1000 + 10 * r + i, 400 + 26.4575 * i, 40.0 * r, "yes", 20, HeightSource::Random);
            b.outer = square(b.outer[0].x, b.outer[0].y, 26.4575);  // 700 m2
            v.push_back(b);
        }
    return v;
}

TEST(InferHeights, ACityOfTaggedBlocksCalibratesTheFabricRule) {
    BuildingParams params;
    ParseReport report;
    std::vector<Building> v = city_of_blocks(3);
    infer_heights(v, {}, params, report);
    for (const Building& b : v) {
        if (b.osm.id >= 1000) EXPECT_EQ(b.height_rule, HeightRule::TypeAndArea) << b.osm.id;
    }
    // The prior would stand them 21 m (six storeys of a fabric of 400 m2 with shared walls); the
    // city's own blocks are five storeys of 15 m, so its 700 m2 blocks stand about 15 x
    // (700 / 400)^0.3 = 17.7 m, not 21.
    const double learnt = median_height(v, 1000, 2000);
    EXPECT_LT(learnt, 19.0);
    EXPECT_GT(learnt, 15.0);
    EXPECT_EQ(report.note_count(ReportKind::BuildingHeights, ReportReason::Calibrated), 16);
    // With fewer than ten tagged, the prior stands (a handful of tagged are the notable ones).
    std::vector<Building> few = city_of_blocks(0);
    for (int i = 0; i < 9; ++i)
        few.push_back(building(100 + i, 20.0 * i, 0, "yes", 15, HeightSource::Levels, 20));
    ParseReport few_report;
    infer_heights(few, {}, params, few_report);
    EXPECT_EQ(few_report.note_count(ReportKind::BuildingHeights, ReportReason::Calibrated), 0);
}

TEST(InferHeights, TaggedHousesOfTheRegionCalibrateTheHouseRule) {
    // A region of one-storey houses with a roof (5.5 m), twenty of them tagged far apart: the
    // untagged houses learn the region's house, not the two storeys of 8 m of the prior.
    BuildingParams params;
    std::vector<Building> v;
    for (int i = 0; i < 20; ++i) v.push_back(building(100 + i, 400.0 * i, 0, "house", 5.5, HeightSource::Tagged, 10));
    for (int i = 0; i < 10; ++i) v.push_back(building(1000 + i, 400.0 * i, 2000, "house", 20, HeightSource::Random, 10));
    ParseReport report;
    infer_heights(v, {}, params, report);
    const double learnt = median_height(v, 1000, 2000);
    EXPECT_LT(learnt, 6.6);
    EXPECT_GT(learnt, 5.0);
}

// The farm (docs/farm.md): each tile gathers the evidence of the buildings in its core; the
// parts concatenated guess as the whole does.
TEST(InferHeights, TheEvidenceOfARegionsPartsIsTheWholes) {
    BuildingParams params;
    std::vector<Building> v = city_of_blocks(3);
    // Rule 3's: ten tagged `yes` buildings far apart, and an untagged one far from all.
    for (int i = 0; i < 10; ++i) v.push_back(building(300 + i, 1000.0 * i, 5000, "yes", 12.0 + 2 * i, HeightSource::Tagged));
    v.push_back(building(4, 5000, 9000, "yes", 5, HeightSource::Random));
    auto west = [](const Building& b) { return b.outer[0].x < 100; };
    auto east = [](const Building& b) { return b.outer[0].x >= 100; };
    const HeightEvidence whole = height_evidence(v, {}, params);
    HeightEvidence parts = height_evidence(v, {}, params, {}, west);
    const HeightEvidence east_part = height_evidence(v, {}, params, {}, east);
    EXPECT_GT(parts.tagged.size(), 0u);
    EXPECT_GT(east_part.tagged.size(), 0u);
    parts.tagged.insert(parts.tagged.end(), east_part.tagged.begin(), east_part.tagged.end());
    parts.calibration.insert(parts.calibration.end(), east_part.calibration.begin(), east_part.calibration.end());
    EXPECT_EQ(parts.tagged.size(), whole.tagged.size());
    EXPECT_EQ(parts.calibration.size(), whole.calibration.size());
    EXPECT_EQ(whole.calibration.size(), 40u) << "the tagged blocks and the ten far apart";

    std::vector<Building> one = v, tiled = v;
    ParseReport one_report, tiled_report;
    infer_heights(one, {}, params, one_report);
    infer_heights(tiled, {}, params, tiled_report, {}, &parts);
    for (size_t i = 0; i < v.size(); ++i) EXPECT_EQ(one[i].height, tiled[i].height) << v[i].osm.id;
    EXPECT_EQ(by_id(one, 4).height_rule, HeightRule::Neighbours);  // rule 3 took part
}

// A tile whose own extract has no tagged blocks guesses with the region's.
TEST(InferHeights, ARegionsEvidenceStandsInForTheExtracts) {
    BuildingParams params;
    const HeightEvidence region = height_evidence(city_of_blocks(3), {}, params);
    std::vector<Building> own = city_of_blocks(0), with_region = own;
    ParseReport own_report, region_report;
    infer_heights(own, {}, params, own_report);
    infer_heights(with_region, {}, params, region_report, {}, &region);
    EXPECT_EQ(own_report.note_count(ReportKind::BuildingHeights, ReportReason::Calibrated), 0);
    EXPECT_EQ(region_report.note_count(ReportKind::BuildingHeights, ReportReason::Calibrated), 16);
    EXPECT_GT(median_height(own, 1000, 2000), 19.0) << "the prior";
    EXPECT_LT(median_height(with_region, 1000, 2000), 19.0) << "the region's five-storey blocks";
}

TEST(InferHeights, SameResultWhateverTheOrder) {
    BuildingParams params;
    std::vector<Building> v;
    for (int i = 0; i < 40; ++i) {
        const bool tagged = i % 3 == 0;
        v.push_back(building(100 + i, 23.0 * (i % 7), 31.0 * (i / 7), i % 2 ? "yes" : "apartments",
                             tagged ? 6.0 + i : 10, tagged ? HeightSource::Tagged : HeightSource::Random,
                             8 + i % 5 * 6));
    }
    std::vector<Building> reversed(v.rbegin(), v.rend());
    ParseReport r1, r2;
    infer_heights(v, {}, params, r1);
    infer_heights(reversed, {}, params, r2);
    for (const Building& b : v) {
        const Building& other = by_id(reversed, b.osm.id);
        EXPECT_EQ(b.height, other.height) << b.osm.id;
        EXPECT_EQ(b.height_rule, other.height_rule) << b.osm.id;
    }
}

// Through the whole pipeline: --hide-height-tags removes the tags before any rule runs, so a
// tagged tower among low tagged houses gets a guess from its kind, not its own 100 m.
TEST(InferHeights, HiddenTagsDoNotLeakThroughThePipeline) {
    const std::string path = (std::filesystem::temp_directory_path() / "infer_heights_test.osm").string();
    {
        std::ofstream osm(path);
        osm << "<?xml version='1.0'?>\n<osm version='0.6'>\n";
        int node = 1;
        auto way = [&](int id, double lon, const std::string& tags) {
            const double d = 0.0002;
            const double lat = 48.0;
            std::string refs;
            const double pts[4][2] = {{lat, lon}, {lat, lon + d}, {lat + d, lon + d}, {lat + d, lon}};
            const int first = node;
            for (const auto& p : pts) {
                osm << "<node id='" << node << "' lat='" << p[0] << "' lon='" << p[1] << "'/>\n";
                refs += "<nd ref='" + std::to_string(node++) + "'/>";
            }
            osm << "<way id='" << id << "'>" << refs << "<nd ref='" << first << "'/><tag k='building' v='yes'/>"
                << tags << "</way>\n";
        };
        way(1, 7.0, "<tag k='height' v='100'/>");
        way(2, 7.0005, "<tag k='building:levels' v='2'/>");
        way(3, 7.0010, "<tag k='height' v='6'/>");
        way(4, 7.0015, "<tag k='height' v='7'/>");
        osm << "</osm>\n";
    }
    ParseJob job;
    job.input = path;
    job.quiet = true;
    ParseReport truth_report;
    const Scene truth = parse_osm_to_scene(job, truth_report);
    ASSERT_EQ(truth.buildings.size(), 4u);
    EXPECT_GE(by_id(truth.buildings, 1).height, 100);
    job.hide_height_tags = 1;
    ParseReport report;
    const Scene hidden = parse_osm_to_scene(job, report);
    std::remove(path.c_str());
    ASSERT_EQ(hidden.buildings.size(), 4u);
    for (const Building& b : hidden.buildings) {
        EXPECT_EQ(b.height_source, HeightSource::Random) << b.osm.id;
        EXPECT_NE(b.height_rule, HeightRule::Tagged) << b.osm.id;
        EXPECT_NE(b.height_rule, HeightRule::Levels) << b.osm.id;
    }
    EXPECT_LT(by_id(hidden.buildings, 1).height, 50) << "the tower saw its own hidden height";
}

}  // namespace
}  // namespace citygen
