// The automatic view: the densest part of a large scene, never inside a hill.
#include <algorithm>

#include <gtest/gtest.h>

#include "render/camera/camera.h"
#include "render/geometry/ground.h"
#include "tests/render/small_town.h"

using namespace citygen;
using namespace citygen::test;

TEST(FramingCamera, StaysAboveAHillWhereItWouldStand) {
    // A ridge rising 3 m per metre (x + y) towards the south-west, where the automatic view stands.
    Scene s = small_town();
    HeightField& f = s.terrain;
    f.origin = {-400, -400};
    f.cell = 10;
    f.nx = f.ny = 81;
    for (uint32_t j = 0; j < f.ny; ++j)
        for (uint32_t i = 0; i < f.nx; ++i) {
            const double x = f.origin.x + i * f.cell, y = f.origin.y + j * f.cell;
            f.heights.push_back(static_cast<float>(std::max(0.0, -3 * (x + y) - 150)));
        }
    const Vec3 flat_eye = framing_camera(small_town(), 50, 480, 270).position();
    ASSERT_LT(flat_eye.z, ground_height(s, flat_eye.x, flat_eye.y)) << "the flat view would be inside the ridge";
    const Vec3 eye = framing_camera(s, 50, 480, 270).position();
    EXPECT_GE(eye.z, ground_height(s, eye.x, eye.y) + kCameraClearance - 1e-6);
}

TEST(FramingCamera, AboveGroundLiftsOnlyWhatIsTooLow) {
    Scene s = small_town();
    s.ground.z = 2;
    EXPECT_EQ(above_ground(s, {1, 2, 3}).z, 2 + kCameraClearance);
    EXPECT_EQ(above_ground(s, {1, 2, 30}).z, 30);
}

TEST(FramingCamera, LooksAtTheDensestPartOfALargeScene) {
    // A town of 100 blocks 5 km east of 10 scattered farms spread over 10 km: the view shows the
    // town from a few hundred metres, not the whole extent from far away.
    Scene s;
    s.header.bounds_min = {-5000, -5000};
    s.header.bounds_max = {5000, 5000};
    s.ground.min = s.header.bounds_min;
    s.ground.max = s.header.bounds_max;
    auto add = [&](double x, double y, double size) {
        Building b;
        b.outer = square(x, y, size);
        b.height = 12;
        s.buildings.push_back(b);
    };
    for (int i = 0; i < 10; ++i) add(-5000 + 1000 * i, -4000 + 900 * i, 30);
    for (int i = 0; i < 10; ++i)
        for (int j = 0; j < 10; ++j) add(3000 + 40 * i, 1000 + 40 * j, 25);
    const Camera camera = framing_camera(s, 50, 480, 270);
    // Where the centre ray meets the ground: in the town.
    const Vec3 p = camera.position(), f = camera.forward();
    ASSERT_LT(f.z, 0);
    const Vec3 seen = p + f * (-p.z / f.z);
    EXPECT_GT(seen.x, 2900);
    EXPECT_LT(seen.x, 3500);
    EXPECT_GT(seen.y, 900);
    EXPECT_LT(seen.y, 1500);
    EXPECT_LT(std::hypot(p.x - seen.x, p.y - seen.y), 1500) << "from a few hundred metres";
}
