// The ground steps at a retaining wall (osmparse/terrain/retaining_wall_steps.h), on synthetic
// fields: the low side (right of the line) lowered by the wall's height within a cell's diagonal
// and blended back over a shoulder, the high side left, a DEM that already steps more left, and
// a road's corridor never dug under.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "common/ground.h"
#include "osmparse/terrain/fit_terrain.h"
#include "osmparse/terrain/retaining_wall_steps.h"

using namespace citygen;

namespace {

// A field of 2 m cells over [-100, 100]^2 with heights h(x, y).
template <class Height>
HeightField field_of(Height h) {
    HeightField f;
    f.origin = {-100, -100};
    f.cell = 2;
    f.nx = f.ny = 101;
    for (uint32_t j = 0; j < f.ny; ++j)
        for (uint32_t i = 0; i < f.nx; ++i) f.heights.push_back(static_cast<float>(h(-100.0 + 2 * i, -100.0 + 2 * j)));
    return f;
}

double node(const HeightField& f, double x, double y) {
    return f.heights[static_cast<size_t>((y + 100) / 2) * f.nx + static_cast<size_t>((x + 100) / 2)];
}

// A wall along y = 1 from x = -40 to 40, eastwards: its low side is the south.
RetainingWall wall_east(double height) {
    RetainingWall w;
    w.line = {{-40, 1}, {0, 1}, {40, 1}};
    w.height = height;
    return w;
}

std::vector<uint8_t> no_ways(const HeightField& f) { return std::vector<uint8_t>(f.heights.size(), 0); }

}  // namespace

TEST(StepTerrainAtWalls, OnAFlatFieldTheLowSideIsLoweredByTheWallsHeight) {
    HeightField f = field_of([](double, double) { return 20.0; });
    ParseReport report;
    step_terrain_at_walls(f, {wall_east(3)}, no_ways(f), report);
    for (double x : {-38.0, -10.0, 0.0, 24.0, 38.0}) {
        EXPECT_FLOAT_EQ(node(f, x, 0), 17) << "the foot, a cell below the line, at " << x;
        EXPECT_NEAR(node(f, x, -2), 17, 0.05) << "3 m from the line: the shoulder's start, at " << x;
        EXPECT_FLOAT_EQ(node(f, x, 2), 20) << "the high side is left, at " << x;
        EXPECT_FLOAT_EQ(node(f, x, 40), 20);
        // The shoulder blends back into the field: lower than the field, higher than the foot.
        EXPECT_GT(node(f, x, -8), 17) << x;
        EXPECT_LT(node(f, x, -8), 20) << x;
        EXPECT_FLOAT_EQ(node(f, x, -30), 20) << "beyond the shoulder, at " << x;
    }
    EXPECT_FLOAT_EQ(node(f, -60, 0), 20) << "the step ends with the wall";
    EXPECT_FLOAT_EQ(node(f, 60, 0), 20);
    // The drawn ground falls by the wall's height across it.
    EXPECT_NEAR(field_surface_height(f, 10, 3) - field_surface_height(f, 10, -1), 3, 0.05);
    EXPECT_EQ(report.note_count(ReportKind::TerrainNodes, ReportReason::TerrainAtRetainingWall), 41);
    EXPECT_GT(report.note_count(ReportKind::TerrainNodes, ReportReason::TerrainRetainingWallShoulder), 0);
}

TEST(StepTerrainAtWalls, TheWaysDirectionSaysWhichSideIsLow) {
    HeightField f = field_of([](double, double) { return 20.0; });
    RetainingWall west = wall_east(3);
    std::reverse(west.line.begin(), west.line.end());  // westwards: the low side is the north
    ParseReport report;
    step_terrain_at_walls(f, {west}, no_ways(f), report);
    EXPECT_FLOAT_EQ(node(f, 0, 2), 17);
    EXPECT_FLOAT_EQ(node(f, 0, 0), 20);
}

TEST(StepTerrainAtWalls, OnASlopeTheFootIsTheHighSidesGroundLessTheHeight) {
    // Rising 0.1 to the north: at the wall's line (y = 1) the ground is 50.1.
    HeightField f = field_of([](double, double y) { return 50 + 0.1 * y; });
    ParseReport report;
    step_terrain_at_walls(f, {wall_east(2)}, no_ways(f), report);
    EXPECT_NEAR(node(f, 0, 0), 48.1, 1e-4);
    EXPECT_NEAR(node(f, 0, -2), 48.1, 0.05);
    EXPECT_NEAR(node(f, 0, 2), 50.2, 1e-4);
}

TEST(StepTerrainAtWalls, WhereTheDemAlreadyFallsFurtherItIsLeft) {
    // A steep fall to the south, 3 m per metre.
    const auto h = [](double, double y) { return 100 + 3 * y; };
    HeightField f = field_of(h);
    ParseReport report;
    step_terrain_at_walls(f, {wall_east(5)}, no_ways(f), report);
    EXPECT_FLOAT_EQ(node(f, 0, 0), static_cast<float>(h(0, 1) - 5)) << "3 m below the line: lowered to 5 m below";
    EXPECT_FLOAT_EQ(node(f, 0, -2), h(0, -2)) << "9 m below the line already: left";
}

TEST(StepTerrainAtWalls, ARoadsCorridorIsNotDugUnder) {
    HeightField f = field_of([](double, double) { return 20.0; });
    RoadEdge road;
    road.centreline = {{-60, -4}, {60, -4}};  // along the wall's foot
    road.width = 4;
    const std::vector<uint8_t> under = way_corridor_nodes(f, {road}, {}, {});
    EXPECT_TRUE(under[static_cast<size_t>((-4 + 100) / 2) * f.nx + 50]);
    EXPECT_FALSE(under[static_cast<size_t>((20 + 100) / 2) * f.nx + 50]);
    ParseReport report;
    step_terrain_at_walls(f, {wall_east(3)}, under, report);
    for (double y : {0.0, -2.0, -4.0, -8.0}) EXPECT_FLOAT_EQ(node(f, 0, y), 20) << y;
    EXPECT_EQ(report.note_count(ReportKind::RetainingWalls, ReportReason::RetainingWallUnderWays), 1);
}

TEST(StepTerrainAtWalls, AClosedWallCounterClockwiseIsAPlatformAboveItsSurroundings) {
    HeightField f = field_of([](double, double) { return 20.0; });
    RetainingWall w;
    w.line = {{-21, -21}, {21, -21}, {21, 21}, {-21, 21}, {-21, -21}};  // counter-clockwise: outside on the right
    w.height = 1.5;
    ParseReport report;
    step_terrain_at_walls(f, {w}, no_ways(f), report);
    EXPECT_FLOAT_EQ(node(f, 0, 0), 20) << "inside";
    for (Vec2 p : {Vec2{0, -22}, Vec2{22, 0}, Vec2{0, 22}, Vec2{-22, 0}, Vec2{-22, -22}})
        EXPECT_FLOAT_EQ(node(f, p.x, p.y), 18.5) << p.x << " " << p.y;
}
