// The sky model: a blue zenith, circumsolar brightening, a red setting sun, point stars.
#include <gtest/gtest.h>

#include "common/rng.h"
#include "render/lights/sky.h"
#include "render/materials/bsdf.h"

using namespace citygen;

TEST(Sky, DaylightIsBlueAboveBrightNearTheSunAndStarsOnlyShowDirectly) {
    const Sky day = Sky::daylight(TimeOfDay::Day);
    const Color zenith = day.radiance({0, 0, 1});
    EXPECT_GT(zenith.z, zenith.x) << "a clear zenith is blue";
    const Vec3 near_sun = normalize(day.sun_direction() + Vec3{0, 0, 0.05});
    const Vec3 away = normalize(Vec3{-day.sun_direction().x, -day.sun_direction().y, 0.5});
    EXPECT_GT(luminance(day.radiance(near_sun)), 2 * luminance(day.radiance(away))) << "circumsolar brightening";
    EXPECT_TRUE(day.in_sun_disc(day.sun_direction()));
    EXPECT_FALSE(day.in_sun_disc(near_sun));

    const Sky sunset = Sky::daylight(TimeOfDay::Sunset);
    EXPECT_LT(sunset.sun_direction().z, 0.1);
    EXPECT_GT(sunset.sun_radiance().x, 2 * sunset.sun_radiance().z) << "the setting sun is red";

    const Sky night = Sky::daylight(TimeOfDay::Night);
    int stars = 0, samples = 0;
    Rng rng(3);
    for (int i = 0; i < 200000; ++i) {
        const Vec3 dir = normalize(Vec3{rng.next_double() - 0.5, rng.next_double() - 0.5, rng.next_double()});
        if (dir.z <= 0.05) continue;
        ++samples;
        const Color direct = night.radiance(dir, true), indirect = night.radiance(dir, false);
        EXPECT_LT(luminance(indirect), 0.01);
        if (luminance(direct) > 20 * luminance(indirect)) ++stars;
    }
    EXPECT_GT(stars, 0) << "the night sky has stars";
    EXPECT_LT(stars, samples / 100) << "stars are points, not a glow";
}
