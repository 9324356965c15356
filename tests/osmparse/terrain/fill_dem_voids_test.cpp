// Filling a DEM grid's voids: from the rim, at the coast as sea level, beyond the DEM flat.
#include <gtest/gtest.h>

#include <cmath>

#include "common/error.h"
#include "osmparse/terrain/fill_dem_voids.h"

using namespace citygen;

namespace {

// A grid of nx x ny nodes 10 m apart, every node covered, heights from f(i, j).
template <typename F>
DemGrid grid(uint32_t nx, uint32_t ny, F f) {
    DemGrid g;
    g.cell = 10;
    g.nx = nx;
    g.ny = ny;
    for (uint32_t j = 0; j < ny; ++j)
        for (uint32_t i = 0; i < nx; ++i) g.heights.push_back(static_cast<float>(f(i, j)));
    g.covered.assign(g.size(), 1);
    return g;
}

double slope(uint32_t i, uint32_t j) { return 100 + 3.0 * i + 1.0 * j; }

void punch(DemGrid& g, uint32_t i0, uint32_t j0, uint32_t i1, uint32_t j1, float value = NAN) {
    for (uint32_t j = j0; j <= j1; ++j)
        for (uint32_t i = i0; i <= i1; ++i) g.heights[g.index(i, j)] = value;
}

}  // namespace

TEST(FillDemVoids, VoidInASlopeIsFilledBetweenItsNeighbours) {
    DemGrid g = grid(20, 20, slope);
    punch(g, 7, 8, 11, 11);  // 5 x 4 nodes
    const VoidCounts counts = fill_dem_voids(g, {});
    EXPECT_EQ(counts.filled, 20);
    EXPECT_EQ(counts.sea, 0);
    for (uint32_t j = 8; j <= 11; ++j)
        for (uint32_t i = 7; i <= 11; ++i) EXPECT_NEAR(g.heights[g.index(i, j)], slope(i, j), 0.05) << i << "," << j;
    EXPECT_FLOAT_EQ(g.heights[g.index(3, 3)], slope(3, 3));  // known nodes untouched
}

TEST(FillDemVoids, HeightsBeyondTheAltitudeLimitsAreVoids) {
    DemGrid g = grid(12, 12, slope);
    g.heights[g.index(4, 4)] = -32768;  // SRTM's no-data value, undeclared
    g.heights[g.index(7, 7)] = 12000;
    const VoidCounts counts = fill_dem_voids(g, {});
    EXPECT_EQ(counts.out_of_range, 2);
    EXPECT_EQ(counts.filled, 2);
    EXPECT_NEAR(g.heights[g.index(4, 4)], slope(4, 4), 0.05);
    EXPECT_NEAR(g.heights[g.index(7, 7)], slope(7, 7), 0.05);
}

// The sea reads 0 in the west half, the land rises in the east: a void surrounded by sea is sea.
TEST(FillDemVoids, VoidAtTheCoastBecomesSeaLevel) {
    DemGrid g = grid(20, 10, [](uint32_t i, uint32_t) { return i < 10 ? (i % 2 ? -2.0 : 0.0) : 40.0 + 5 * i; });
    punch(g, 3, 3, 6, 6);
    const VoidCounts counts = fill_dem_voids(g, {});
    EXPECT_EQ(counts.sea, 16);
    EXPECT_EQ(counts.filled, 0);
    EXPECT_EQ(g.heights[g.index(4, 4)], 0);
}

// A void in a cliff above the sea: a third of its rim is at sea level, the rest high. Set to 0 it
// would be a pit in the cliff; filled, it keeps the slope.
TEST(FillDemVoids, VoidInACliffAboveTheSeaKeepsTheCliff) {
    DemGrid g = grid(12, 20, [](uint32_t, uint32_t j) { return j < 6 ? 0.0 : 15.0 * (j - 5); });
    punch(g, 4, 6, 7, 12);  // from just above the shore up the cliff
    const VoidCounts counts = fill_dem_voids(g, {});
    EXPECT_EQ(counts.sea, 0);
    EXPECT_EQ(counts.filled, 28);
    for (uint32_t j = 6; j <= 12; ++j) {
        const float h = g.heights[g.index(5, j)];
        EXPECT_GT(h, 0) << j;
        EXPECT_LT(h, 15.0 * (13 - 5)) << j;
    }
    EXPECT_GT(g.heights[g.index(5, 12)], g.heights[g.index(5, 7)] + 30);  // still climbing
}

// Where the scene's sea covers a void, it is sea level whatever its rim says.
TEST(FillDemVoids, VoidInTheScenesSeaIsSeaLevel) {
    DemGrid g = grid(10, 10, slope);
    punch(g, 2, 2, 4, 4);
    std::vector<uint8_t> sea(g.size(), 0);
    for (uint32_t j = 2; j <= 4; ++j) sea[g.index(2, j)] = 1;
    const VoidCounts counts = fill_dem_voids(g, sea);
    EXPECT_EQ(counts.sea, 3);
    EXPECT_EQ(counts.filled, 6);
    EXPECT_EQ(g.heights[g.index(2, 3)], 0);
    EXPECT_GT(g.heights[g.index(4, 3)], 50);
}

// A DEM that covers the west half only: the east takes the height at the DEM's edge, row by row.
TEST(FillDemVoids, NodesOutsideEveryDemTakeTheNearestEdgeHeight) {
    DemGrid g = grid(10, 6, slope);
    for (uint32_t j = 0; j < 6; ++j)
        for (uint32_t i = 5; i < 10; ++i) g.covered[g.index(i, j)] = 0, g.heights[g.index(i, j)] = NAN;
    const VoidCounts counts = fill_dem_voids(g, {});
    EXPECT_EQ(counts.outside, 30);
    for (uint32_t j = 0; j < 6; ++j)
        for (uint32_t i = 5; i < 10; ++i) EXPECT_FLOAT_EQ(g.heights[g.index(i, j)], slope(4, j)) << i << "," << j;
    for (float h : g.heights) EXPECT_TRUE(std::isfinite(h));
}

TEST(FillDemVoids, AGridWithoutAnyHeightIsRefused) {
    DemGrid g = grid(5, 5, [](uint32_t, uint32_t) { return NAN; });
    EXPECT_THROW(fill_dem_voids(g, {}), Error);
}
