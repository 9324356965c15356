#include "render/lights/light_bounds.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

namespace citygen {
namespace {

double angle_between(Vec3 a, Vec3 b) { return std::acos(std::clamp(dot(normalize(a), normalize(b)), -1.0, 1.0)); }
double cone_angle(const LightBounds& b) { return std::acos(std::clamp(double(b.cos_theta_o), -1.0, 1.0)); }

LightBounds cone(Vec3 axis, double angle) {
    LightBounds b;
    b.set_box({0, 0, 0}, {1, 1, 1});
    b.phi = 1;
    b.set_axis(axis);
    b.cos_theta_o = static_cast<float>(std::cos(angle));
    return b;
}

// The joined cone holds both: every normal either cone allows (its axis tilted by up to its
// angle) lies within the union's angle of the union's axis. Directions (angle 0) inside and
// outside the other cone, in either order, and cones of every width.
TEST(LightBounds, TheUnionsConeHoldsBothCones) {
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> unit(0, 1);
    auto direction = [&] {
        const double z = 2 * unit(rng) - 1, a = 2 * kPi * unit(rng), r = std::sqrt(1 - z * z);
        return Vec3{r * std::cos(a), r * std::sin(a), z};
    };
    int inside = 0, outside = 0;
    for (int i = 0; i < 20000; ++i) {
        const LightBounds wide = cone(direction(), i % 3 == 0 ? 0.0 : kPi * unit(rng) * 0.9);
        const LightBounds single = cone(direction(), 0.0);
        (angle_between(wide.axis(), single.axis()) <= cone_angle(wide) ? inside : outside)++;
        for (const LightBounds& u : {union_of(wide, single), union_of(single, wide)}) {
            ASSERT_EQ(u.phi, 2.0f);
            if (u.cos_theta_o <= -1) continue;  // every direction
            const double slack = 1e-4;
            EXPECT_LE(angle_between(u.axis(), wide.axis()) + cone_angle(wide), cone_angle(u) + slack);
            EXPECT_LE(angle_between(u.axis(), single.axis()), cone_angle(u) + slack);
        }
    }
    EXPECT_GT(inside, 1000);  // both cases were met
    EXPECT_GT(outside, 1000);
}

// A pane's direction within a cluster's cone leaves the cone as it was; one just outside widens it.
TEST(LightBounds, ADirectionWithinTheConeKeepsItADirectionOutsideWidensIt) {
    const LightBounds fan = cone({1, 0, 0}, 0.5);
    const LightBounds within = union_of(fan, cone({std::cos(0.4), std::sin(0.4), 0}, 0));
    EXPECT_EQ(within.cos_theta_o, fan.cos_theta_o);
    EXPECT_EQ(within.w[0], fan.w[0]);
    const LightBounds beyond = union_of(cone({std::cos(0.6), std::sin(0.6), 0}, 0), fan);
    EXPECT_LT(beyond.cos_theta_o, fan.cos_theta_o);
    EXPECT_NEAR(cone_angle(beyond), 0.55, 1e-3);  // half of 0.5 + 0.6 + 0 (the two cones' span)
}

// A join that keeps a cluster's axis normalizes it again, as set_axis(axis()) does: a float
// axis normalized once may move by an ulp when normalized again, and the tree's bits depend on
// it. The joins skip that work only once it is known not to move the axis.
TEST(LightBounds, AKeptAxisIsNormalizedAgainAsSetAxisWould) {
    std::mt19937_64 rng(5);
    std::uniform_real_distribution<double> unit(-1, 1);
    auto renormalized = [](const LightBounds& b) {
        LightBounds r = b;
        r.set_axis(r.axis());
        return r;
    };
    auto same_axis = [](const LightBounds& a, const LightBounds& b) {
        return a.w[0] == b.w[0] && a.w[1] == b.w[1] && a.w[2] == b.w[2];
    };
    int moved = 0;
    for (int i = 0; i < 20000; ++i) {
        const LightBounds fan = cone({unit(rng), unit(rng), unit(rng)}, 0.5);
        const LightBounds once = renormalized(fan), twice = renormalized(once);
        moved += !same_axis(once, fan);
        // A direction within the cone, joined once and then again; the cone joined with itself.
        LightBounds joined = union_of(fan, cone(fan.axis(), 0));
        ASSERT_TRUE(same_axis(joined, once));
        joined.join(cone(fan.axis(), 0));
        ASSERT_TRUE(same_axis(joined, twice));
        ASSERT_TRUE(same_axis(union_of(fan, fan), once));
        ASSERT_TRUE(same_axis(union_of(union_of(fan, fan), once), twice));
    }
    EXPECT_GT(moved, 10);  // axes that move when normalized again were met
}

}  // namespace
}  // namespace citygen
