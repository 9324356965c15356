// StairPlan::line_height: the straight line between a stair's ends, held level past them, which
// the GeoJSON gives a stair's polygon.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "common/scene.h"
#include "common/stairs.h"

using namespace citygen;

// Between the ends, a vertex lies on the line between them, within one riser of its tread.
TEST(StairPlan, LineHeightIsWithinARiserOfTheTread) {
    StairPlan plan;
    plan.low = {0, 0}, plan.high = {10, 0}, plan.z_low = 1, plan.z_high = 4, plan.steps = 17;
    for (double x = -2; x <= 12; x += 0.37) {
        const double z = plan.line_height({x, 3});
        const double t = std::min(std::max(x / 10, 0.0), 1.0);
        EXPECT_NEAR(z, 1 + 3 * t, 1e-12);
        const int k = std::min(std::max(static_cast<int>(std::floor(x / 10 * 17)), 0), 16);
        const double tread = plan.z_low + (k + 1) * plan.rise();
        EXPECT_LE(z, tread + 1e-12) << x;
        EXPECT_GE(z, tread - plan.rise() - 1e-12) << x;
    }
}

namespace {

// Steps 2 m wide from y = -20 to 20 on a field of 1 m cells over [-40, 40]^2 rising 30% to the
// north, with a bump `bump` m high across their middle, exp(-y^2 / spread) wide.
Scene steps_on_slope(double bump, double spread = 50) {
    Scene s;
    HeightField& f = s.terrain;
    f.origin = {-40, -40};
    f.cell = 1;
    f.nx = f.ny = 81;
    for (uint32_t j = 0; j < f.ny; ++j)
        for (uint32_t i = 0; i < f.nx; ++i) {
            const double y = f.origin.y + j;
            f.heights.push_back(static_cast<float>(50 + 0.3 * y + bump * std::exp(-(y * y) / spread)));
        }
    PathEdge steps;
    steps.path_class = PathClass::Steps;
    steps.centreline = {{0, -20}, {0, 20}};
    steps.width = 2;
    steps.quad = {{1, -20}, {1, 20}, {-1, 20}, {-1, -20}};
    s.paths = {steps};
    return s;
}

}  // namespace

TEST(PlanStair, AStairTheGroundStillBuriesIsDrapedInstead) {
    StairPlan plan;
    const Scene slope = steps_on_slope(0);
    EXPECT_TRUE(plan_stair(slope, slope.paths[0], &plan)) << "on a plain slope: a stair";
    EXPECT_EQ(plan.steps, static_cast<int>(std::ceil(12 / kStairMaxRiser - 1e-9)));
    // A bump of 0.3 m covers no tread by more than a riser: still a stair.
    const Scene low_bump = steps_on_slope(0.3);
    EXPECT_TRUE(plan_stair(low_bump, low_bump.paths[0], &plan));
    // A bump of 2 m the cut could not take away (beside another way's corridor) hiding the treads
    // over 18 m of the 40: a stair hidden in part.
    const Scene hill = steps_on_slope(2);
    EXPECT_TRUE(plan_stair(hill, hill.paths[0], &plan));
    // Hiding them over 37 m: the stair between the ends is there to cut to, but what is drawn is
    // the draped strip.
    const Scene buried = steps_on_slope(2, 200);
    EXPECT_TRUE(stair_between_ends(buried.terrain, buried.paths[0], &plan));
    EXPECT_FALSE(plan_stair(buried, buried.paths[0], &plan));
}
