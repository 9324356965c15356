// ring_is_simple: the pairwise test for small rings and CGAL's sweep agree.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "osmparse/polygons/ring_is_simple.h"

using namespace citygen;

// Defect 5: the pairwise test took 48 s at 100k points. Small rings still use a pairwise test,
// larger ones CGAL's sweep: both must give the same answer, degenerate rings included.
TEST(RingIsSimple, AgreesWithTheSweep) {
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> coord(0, 6), count(3, 12);
    int simple = 0;
    for (int trial = 0; trial < 30000; ++trial) {
        Ring ring;
        for (int i = count(rng); i > 0; --i) ring.push_back({double(coord(rng)), double(coord(rng))});
        ASSERT_EQ(ring_is_simple(ring), ring_is_simple_sweep(ring)) << "trial " << trial;
        simple += ring_is_simple(ring);
    }
    EXPECT_GT(simple, 100);
    EXPECT_FALSE(ring_is_simple({{0, 0}, {2, 0}, {1, 0}, {1, 1}}));  // a spike folding back
    EXPECT_FALSE(ring_is_simple({{0, 0}, {1, 0}, {2, 0}}));          // collinear
    EXPECT_TRUE(ring_is_simple({{0, 0}, {1, 0}, {2, 0}, {1, 1}}));   // collinear neighbours are fine
    Ring circle;
    for (int i = 0; i < 100000; ++i) circle.push_back({std::cos(i * 2 * kPi / 100000), std::sin(i * 2 * kPi / 100000)});
    EXPECT_TRUE(ring_is_simple(circle));
    std::swap(circle[10], circle[50000]);
    EXPECT_FALSE(ring_is_simple(circle));
}
