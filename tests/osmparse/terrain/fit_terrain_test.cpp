// The field fitted to roads, paths and still water (osmparse/terrain/fit_terrain.h), on
// synthetic fields: a plane slope, a hill; and the default cell.
#include <gtest/gtest.h>

#include <cmath>

#include "common/bridge_deck.h"
#include "common/ground.h"
#include "common/stairs.h"
#include "osmparse/terrain/fit_terrain.h"
#include "osmparse/terrain/read_dem.h"

using namespace citygen;

namespace {

// A field of 1 m cells over [-100, 100]^2 with heights h(x, y).
template <class Height>
HeightField field_of(Height h, double cell = 1) {
    HeightField f;
    f.origin = {-100, -100};
    f.cell = cell;
    f.nx = f.ny = static_cast<uint32_t>(200 / cell) + 1;
    for (uint32_t j = 0; j < f.ny; ++j)
        for (uint32_t i = 0; i < f.nx; ++i)
            f.heights.push_back(static_cast<float>(h(f.origin.x + i * cell, f.origin.y + j * cell)));
    return f;
}

HeightField slope_north(double grade, double cell = 1) {
    return field_of([grade](double, double y) { return 50 + grade * y; }, cell);
}

RoadEdge road(std::vector<Vec2> centreline, double width, bool sidewalks = false) {
    RoadEdge r;
    r.centreline = std::move(centreline);
    r.width = width;
    r.sidewalk_left = r.sidewalk_right = sidewalks;
    return r;
}

// The drawn ground's slope across a road of `width` at p, its axis along `along` (unit).
double cross_slope(const HeightField& f, Vec2 p, Vec2 along, double width) {
    const Vec2 n{-along.y, along.x};
    const Vec2 l = p + n * (width / 2), r = p - n * (width / 2);
    return std::fabs(field_surface_height(f, l.x, l.y) - field_surface_height(f, r.x, r.y)) / width;
}

}  // namespace

TEST(FitTerrainToWays, ARoadAlongTheContoursOfASlopeIsLevelAcrossIt) {
    HeightField f = slope_north(0.15);
    const RoadEdge r = road({{-60, 0}, {60, 0}}, 7, true);
    EXPECT_NEAR(cross_slope(f, {0, 0}, {1, 0}, 7), 0.15, 1e-6);  // the DEM tilts it
    ParseReport report;
    fit_terrain_to_ways(f, {r}, {}, {}, report);
    for (double x : {-40.0, -10.0, 0.0, 25.5, 40.0}) {
        EXPECT_LT(cross_slope(f, {x, 0}, {1, 0}, 7), 1e-4) << x;
        EXPECT_LT(cross_slope(f, {x, 0}, {1, 0}, 7 + 2 * 2), 1e-4) << "the sidewalks too, at " << x;
        EXPECT_NEAR(field_surface_height(f, x, 0), 50, 0.01) << "the profile on a plane is the plane";
    }
    // Cut on the uphill side, fill on the downhill side, and the DEM again beyond the shoulder.
    EXPECT_LT(f.at(0, 10), 50 + 0.15 * 10);
    EXPECT_GT(f.at(0, -10), 50 - 0.15 * 10);
    EXPECT_FLOAT_EQ(f.at(0, 30), 50 + 0.15 * 30);
    EXPECT_FLOAT_EQ(f.at(0, -30), 50 - 0.15 * 30);
    EXPECT_GT(report.note_count(ReportKind::TerrainNodes, ReportReason::TerrainUnderWay), 0);
    EXPECT_GT(report.note_count(ReportKind::TerrainNodes, ReportReason::TerrainWayShoulder), 0);
}

TEST(FitTerrainToWays, ARoadUpASlopeKeepsItsGradeAndIsLevelAcrossOnCoarseCells) {
    for (double cell : {1.0, 4.0}) {
        HeightField f = slope_north(0.1, cell);
        ParseReport report;
        fit_terrain_to_ways(f, {road({{3, -60}, {3, 60}}, 6)}, {}, {}, report);
        for (double y : {-30.0, 0.0, 30.0}) {
            EXPECT_LT(cross_slope(f, {3, y}, {0, 1}, 6), 1e-4) << cell << " " << y;
            const double grade = (field_surface_height(f, 3, y + 5) - field_surface_height(f, 3, y - 5)) / 10;
            EXPECT_NEAR(grade, 0.1, 1e-3) << cell << " " << y;
        }
    }
}

TEST(FitTerrainToWays, AHillsBumpsAreSmoothedAlongTheRoadAndItsEndsMeetTheNextRoad) {
    // Noise of a fine surface model (a 1.5 m ripple 4 m long) on a hill.
    HeightField f = field_of([](double x, double y) {
        return 30 * std::exp(-(x * x + y * y) / (2 * 40 * 40)) + 1.5 * std::sin(x * 2 * M_PI / 4);
    });
    const HeightField raw = f;
    ParseReport report;
    fit_terrain_to_ways(f, {road({{-80, 0}, {0, 0}}, 6), road({{0, 0}, {80, 0}}, 6)}, {}, {}, report);
    double raw_rough = 0, fitted_rough = 0;
    for (double x = -60; x <= 60; x += 0.5) {
        const auto second = [x](const HeightField& g) {
            return std::fabs(field_surface_height(g, x - 1, 0) - 2 * field_surface_height(g, x, 0) +
                             field_surface_height(g, x + 1, 0));
        };
        raw_rough = std::max(raw_rough, second(raw));
        fitted_rough = std::max(fitted_rough, second(f));
        EXPECT_LT(cross_slope(f, {x, 0}, {1, 0}, 6), 1e-3) << x;
    }
    EXPECT_LT(fitted_rough, raw_rough / 10) << "the ripple is smoothed out of the profile";
    // Smoothing at 10 m lowers a hill 40 m wide by 40^2 / (40^2 + 10^2): 6%, not more.
    EXPECT_NEAR(field_surface_height(f, 0, 0), 30 * 40 * 40 / (40 * 40 + 10 * 10), 0.5) << "the hill stays";
}

TEST(FitTerrainToWays, ABridgeIsNotFittedAndTheGroundUnderItsDeckIsCarvedBelowIt) {
    // A hill the bridge crosses (what a coarse DEM makes of a road in a cutting under it): the
    // deck runs straight between the roads at its ends, and the hill under it is lowered.
    HeightField f = field_of([](double x, double y) { return 50 + 12 * std::exp(-(x * x + y * y) / 400); });
    const HeightField raw = f;
    RoadEdge west = road({{-90, 0}, {-40, 0}}, 6), east = road({{40, 0}, {90, 0}}, 6);
    RoadEdge bridge = road({{-40, 0}, {40, 0}}, 6);
    west.from_node = 1, west.to_node = 2, bridge.from_node = 2, bridge.to_node = 3, east.from_node = 3, east.to_node = 4;
    bridge.bridge = true;
    bridge.quad = {{-34, -3}, {34, -3}, {34, 3}, {-34, 3}};  // from the joints' edges, 6 m from the nodes
    PathEdge steps;
    steps.centreline = {{20, -90}, {20, -50}};
    steps.width = 2;
    steps.path_class = PathClass::Steps;
    ParseReport report;
    const std::vector<RoadEdge> roads = {west, bridge, east};
    fit_terrain_to_ways(f, roads, {steps}, {}, report);
    const DeckLine deck = bridge_decks(f, 0, roads)[1];
    ASSERT_TRUE(deck.valid);
    EXPECT_NEAR(deck.za, field_surface_height(f, -40, 0), 1e-6) << "the deck meets the road at its end";
    EXPECT_NEAR(deck.za, raw.at(-40, 0), 1) << "near the ground there";
    for (Vec2 c : bridge.quad)
        EXPECT_NEAR(field_surface_height(f, c.x, c.y), deck_height(deck, c), 1e-3) << "the deck's end on its abutment";
    for (double x = -25; x <= 25; x += 0.5)
        for (double y : {-3.0, 0.0, 3.0})
            EXPECT_LE(field_surface_height(f, x, y), deck_height(deck, {x, y}) - kDeckThickness) << x << " " << y;
    EXPECT_LT(f.at(0, 0), raw.at(0, 0) - 12) << "the hill is carved";
    EXPECT_FLOAT_EQ(f.at(0, 40), raw.at(0, 40)) << "beyond the deck the DEM";
    EXPECT_FLOAT_EQ(f.at(20, -70), raw.at(20, -70)) << "steps stay on the DEM";
    EXPECT_EQ(report.note_count(ReportKind::RoadEdges, ReportReason::BridgeOnItsDeck), 1);
    EXPECT_GT(report.note_count(ReportKind::TerrainNodes, ReportReason::TerrainUnderDeck), 0);
    EXPECT_GT(report.note_count(ReportKind::TerrainNodes, ReportReason::TerrainUnderAbutment), 0);
}

TEST(FitTerrainToWays, AFootbridgeIsNotFittedAndTheGroundUnderItsDeckIsCarvedBelowIt) {
    // The same hill as above, crossed by footways: paths and rails keep decks as roads do.
    HeightField f = field_of([](double x, double y) { return 50 + 12 * std::exp(-(x * x + y * y) / 400); });
    const HeightField raw = f;
    auto path = [](int64_t from, int64_t to, Vec2 a, Vec2 b, bool bridge) {
        PathEdge p;
        p.from_node = from;
        p.to_node = to;
        p.centreline = {a, b};
        p.width = 2;
        p.bridge = bridge;
        p.quad = {{a.x + 1, -1}, {b.x - 1, -1}, {b.x - 1, 1}, {a.x + 1, 1}};
        return p;
    };
    const std::vector<PathEdge> paths = {path(1, 2, {-90, 0}, {-40, 0}, false), path(2, 3, {-40, 0}, {40, 0}, true),
                                         path(3, 4, {40, 0}, {90, 0}, false)};
    ParseReport report;
    fit_terrain_to_ways(f, {}, paths, {}, report);
    const DeckLine deck = bridge_decks(f, 0, paths)[1];
    ASSERT_TRUE(deck.valid);
    EXPECT_NEAR(deck.za, field_surface_height(f, -40, 0), 1e-6) << "the deck meets the path at its end";
    for (double x = -25; x <= 25; x += 0.5)
        EXPECT_LE(field_surface_height(f, x, 0), deck_height(deck, {x, 0}) - kDeckThickness) << x;
    EXPECT_LT(f.at(0, 0), raw.at(0, 0) - 12) << "the hill is carved, not the path laid over it";
    EXPECT_EQ(report.note_count(ReportKind::PathEdges, ReportReason::BridgeOnItsDeck), 1);
}

TEST(RaisePiers, APierIntoTheSeaIsFlatAtItsDeckAndTheRestIsLeftAsItWas) {
    HeightField f = slope_north(0.1);  // 40 m at y = -100 .. 60 m at y = 100: the DEM's noise at sea
    const HeightField raw = f;
    LandCover sea, pier, square;
    sea.cover = LandCoverClass::Sea;
    sea.outer = {{-100, -100}, {100, -100}, {100, 0}, {-100, 0}};
    pier.cover = square.cover = LandCoverClass::Paved;
    pier.outer = {{-5, -60}, {5, -60}, {5, 10}, {-5, 10}};      // from the quay into the sea
    square.outer = {{40, 20}, {60, 20}, {60, 40}, {40, 40}};    // on land
    ParseReport report;
    raise_piers(f, {sea, pier, square}, report);
    for (double y : {-59.0, -30.0, -1.0})
        for (double x : {-4.0, 0.0, 4.5}) EXPECT_NEAR(field_surface_height(f, x, y), kPierDeck, 1e-6) << x << " " << y;
    EXPECT_FLOAT_EQ(f.at(0, 5), raw.at(0, 5)) << "the pier's root on land keeps the ground";
    EXPECT_FLOAT_EQ(f.at(50, 30), raw.at(50, 30)) << "a square on land keeps the ground";
    EXPECT_FLOAT_EQ(f.at(-50, -50), raw.at(-50, -50)) << "the open sea is render's to lower";
    EXPECT_GT(report.note_count(ReportKind::TerrainNodes, ReportReason::TerrainUnderPier), 70 * 10);
}

TEST(FitTerrainToWays, AFootwayBesideARoadIsLevelWithTheRoad) {
    HeightField f = slope_north(0.15);
    PathEdge footway;
    footway.centreline = {{-50, 5}, {50, 5}};
    footway.width = 2;
    ParseReport report;
    fit_terrain_to_ways(f, {road({{-50, 0}, {50, 0}}, 7)}, {footway}, {}, report);
    EXPECT_LT(cross_slope(f, {0, 0}, {1, 0}, 7), 1e-4) << "the road is not tilted towards the footway";
}

TEST(LevelStillWater, APondOnASlopeIsLevelAtItsLowestShoreAndARiverDownAValleyIsNot) {
    HeightField f = slope_north(0.1);
    const HeightField raw = f;
    const Ring pond = {{-10, -10}, {10, -10}, {10, 10}, {-10, 10}};       // falls 2 m
    const Ring river = {{40, -90}, {60, -90}, {60, 90}, {40, 90}};        // falls 18 m
    std::vector<LandCover> cover = {{{OsmType::Way, 1}, LandCoverClass::Water, pond, {}},
                                    {{OsmType::Way, 2}, LandCoverClass::Water, river, {}},
                                    {{OsmType::Way, 3}, LandCoverClass::Green, {{-90, 30}, {-60, 30}, {-60, 60}}, {}}};
    ParseReport report;
    level_still_water(f, cover, report);
    for (double x : {-9.5, 0.0, 9.5})
        for (double y : {-9.5, 0.0, 9.5}) EXPECT_NEAR(field_surface_height(f, x, y), 49, 1e-4) << x << " " << y;
    EXPECT_FLOAT_EQ(f.at(50, 50), raw.at(50, 50));
    EXPECT_FLOAT_EQ(f.at(-70, 40), raw.at(-70, 40));
    EXPECT_FLOAT_EQ(f.at(0, 20), raw.at(0, 20));
    EXPECT_EQ(report.note_count(ReportKind::LandCoverWater, ReportReason::WaterLevelled), 1);
    EXPECT_EQ(report.note_count(ReportKind::LandCoverWater, ReportReason::WaterOnASlope), 1);
}

TEST(DefaultFieldCell, TheFinerOfTheDemAndTheRoadFitCellWithinTheNodeBudget) {
    Box2 town;
    town.extend({-2000, -2000});
    town.extend({2000, 2000});
    EXPECT_EQ(default_field_cell(81, town), kRoadFitCell);
    EXPECT_EQ(default_field_cell(1, town), 1);
    Box2 country;
    country.extend({-20000, -15000});
    country.extend({20000, 15000});
    const double cell = default_field_cell(30, country);
    EXPECT_GT(cell, kRoadFitCell);
    EXPECT_LE((40000 / cell + 7) * (30000 / cell + 7), static_cast<double>(kDefaultFieldNodes));
    EXPECT_LE(cell, 30) << "never coarser than it has to be";
}

TEST(NoteSteps, StepsUpASlopeAreCountedAsAStairAndStepsAlongItAsDraped) {
    Scene s;
    s.terrain = slope_north(0.3);
    const auto steps = [](Vec2 a, Vec2 b) {
        PathEdge p;
        p.path_class = PathClass::Steps;
        p.centreline = {a, b};
        p.width = 2;
        const Vec2 n = perp_left(normalize(b - a));
        p.quad = {a - n, b - n, b + n, a + n};
        return p;
    };
    s.paths = {steps({0, -20}, {0, -10}), steps({0, 10}, {20, 10}), steps({10, 20}, {10, 30})};
    s.paths.push_back(steps({20, 20}, {20, 30}));
    s.paths.back().path_class = PathClass::Footway;  // not steps: not counted
    ParseReport report;
    note_steps(s, report);
    EXPECT_EQ(report.note_count(ReportKind::PathEdges, ReportReason::StepsAsStair), 2);
    EXPECT_EQ(report.note_count(ReportKind::PathEdges, ReportReason::StepsOnTheGround), 1);
    s.terrain = {};
    ParseReport flat;
    note_steps(s, flat);
    EXPECT_EQ(flat.note_count(ReportKind::PathEdges, ReportReason::StepsAsStair), 0);
}

TEST(FitTerrainToWays, TheGroundThatWouldBuryASteepStairIsCutDownToItsLine) {
    // A slope of 30% with a bump 2 m high across the middle of steps climbing it: the stair's
    // treads rise along the line between its ends, which the bump would cover.
    HeightField f = field_of([](double, double y) { return 50 + 0.3 * y + 2 * std::exp(-(y * y) / 50); });
    const HeightField raw = f;
    PathEdge steps;
    steps.path_class = PathClass::Steps;
    steps.centreline = {{0, -20}, {0, 20}};
    steps.width = 2;
    steps.quad = {{1, -20}, {1, 20}, {-1, 20}, {-1, -20}};
    ParseReport report;
    fit_terrain_to_ways(f, {}, {steps}, {}, report);
    StairPlan plan;
    ASSERT_TRUE(stair_between_ends(f, steps, &plan));
    EXPECT_NEAR(plan.z_low, raw.at(0, -20), 0.05) << "the ends stay where they were";
    for (double y = -19.5; y < 20; y += 0.5)
        for (double x : {-1.0, 0.0, 1.0}) {
            const double line = plan.z_low + (y + 20) / 40 * (plan.z_high - plan.z_low);
            EXPECT_LE(field_surface_height(f, x, y), line + 1e-3) << x << " " << y;
        }
    EXPECT_GT(field_surface_height(raw, 0, 0), plan.z_low + 0.5 * (plan.z_high - plan.z_low) + 1.5) << "the bump was there";
    EXPECT_FLOAT_EQ(f.at(30, 0), raw.at(30, 0)) << "beyond the shoulder the DEM";
    EXPECT_GT(report.note_count(ReportKind::TerrainNodes, ReportReason::TerrainUnderStair), 0);
}
