// HeightField::at: bilinear between the nodes, the edge's height beyond the grid.
#include <gtest/gtest.h>

#include "common/scene.h"

using namespace citygen;

namespace {

// 4 x 3 nodes 10 m apart from (100, 200), heights of the plane 2 + 0.5 x' + 0.25 y' (x', y' from the origin).
HeightField plane() {
    HeightField f;
    f.origin = {100, 200};
    f.cell = 10;
    f.nx = 4;
    f.ny = 3;
    for (uint32_t j = 0; j < f.ny; ++j)
        for (uint32_t i = 0; i < f.nx; ++i) f.heights.push_back(static_cast<float>(2 + 0.5 * 10 * i + 0.25 * 10 * j));
    return f;
}

}  // namespace

TEST(HeightField, BilinearBetweenNodesIsThePlane) {
    const HeightField f = plane();
    for (double x = 100; x <= 130; x += 2.5)
        for (double y = 200; y <= 220; y += 2.5) EXPECT_NEAR(f.at(x, y), 2 + 0.5 * (x - 100) + 0.25 * (y - 200), 1e-5);
}

TEST(HeightField, NodesAreRowMajorSouthToNorth) {
    HeightField f = plane();
    f.heights[1 * f.nx + 2] = 50;  // node (2, 1)
    EXPECT_DOUBLE_EQ(f.at(120, 210), 50);
    EXPECT_DOUBLE_EQ(f.at(125, 210), (50 + f.heights[1 * f.nx + 3]) / 2);
}

TEST(HeightField, BeyondTheGridTheEdgeHeight) {
    const HeightField f = plane();
    EXPECT_DOUBLE_EQ(f.at(0, 0), f.heights[0]);
    EXPECT_DOUBLE_EQ(f.at(1000, 1000), f.heights.back());
    EXPECT_NEAR(f.at(115, -50), f.at(115, 200), 1e-9);
}

TEST(HeightField, AnEmptyFieldIsFlat) {
    const HeightField f;
    EXPECT_TRUE(f.empty());
    EXPECT_EQ(f.at(5, 5), 0);
}
