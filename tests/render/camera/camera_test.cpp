// The automatic view on a height field: never inside a hill.
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
