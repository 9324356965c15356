// StairPlan::line_height: the straight line between a stair's ends, held level past them, which
// the GeoJSON gives a stair's polygon.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

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
