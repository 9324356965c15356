// Scene format 1.2: the height field round-trips; without one the scene has format 1.1's bytes
// but for the version; a field the limits refuse is refused by the loader with one line.
#include <gtest/gtest.h>

#include <cmath>

#include "common/error.h"
#include "common/scene_io.h"
#include "common/scene_limits.h"

using namespace citygen;

namespace {

Scene with_terrain() {
    Scene s;
    s.header.bounds_min = {-50, -40};
    s.header.bounds_max = {50, 40};
    HeightField& t = s.terrain;
    t.origin = {-60, -50};
    t.cell = 20;
    t.nx = 7;
    t.ny = 6;
    for (uint32_t k = 0; k < t.nx * t.ny; ++k) t.heights.push_back(0.5f * static_cast<float>(k));
    t.reference_altitude = 12;
    t.vertical_datum = "EGM96 geoid";
    return s;
}

std::string refusal(const Scene& s) {
    const std::vector<uint8_t> bytes = encode_scene(s);
    try {
        decode_scene(bytes.data(), bytes.size(), "bad.scene");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(SceneIoTerrain, HeightFieldRoundTrips) {
    const Scene s = with_terrain();
    const std::vector<uint8_t> bytes = encode_scene(s);
    const Scene back = decode_scene(bytes.data(), bytes.size(), "terrain.scene");
    EXPECT_EQ(back.header.format_minor, 2);
    EXPECT_EQ(back.terrain.origin, s.terrain.origin);
    EXPECT_EQ(back.terrain.cell, 20);
    EXPECT_EQ(back.terrain.nx, 7u);
    EXPECT_EQ(back.terrain.ny, 6u);
    EXPECT_EQ(back.terrain.heights, s.terrain.heights);
    EXPECT_EQ(back.terrain.reference_altitude, 12);
    EXPECT_EQ(back.terrain.vertical_datum, "EGM96 geoid");
    EXPECT_EQ(encode_scene(back), bytes);
}

// The field is a table at the end of Scene, absent when empty (the golden scenes check that the
// rest keeps format 1.1's bytes).
TEST(SceneIoTerrain, AnEmptyFieldIsLeftOutOfTheFile) {
    Scene s = with_terrain();
    const size_t with = encode_scene(s).size();
    s.terrain = HeightField();
    const std::vector<uint8_t> bytes = encode_scene(s);
    EXPECT_GE(with - bytes.size(), 4 * 42u);
    EXPECT_TRUE(decode_scene(bytes.data(), bytes.size(), "flat.scene").terrain.empty());
}

TEST(SceneIoTerrain, AFieldWhoseSizeIsNotNxTimesNyIsRefused) {
    Scene s = with_terrain();
    s.terrain.heights.pop_back();
    EXPECT_NE(refusal(s).find("terrain has 41 heights for 7 x 6 nodes"), std::string::npos) << refusal(s);
}

TEST(SceneIoTerrain, FieldsBeyondTheLimitsAreRefused) {
    auto refused = [](void (*change)(Scene&), const std::string& words) {
        Scene s = with_terrain();
        change(s);
        const std::string message = refusal(s);
        EXPECT_NE(message.find(words), std::string::npos) << words << ": " << message;
        EXPECT_EQ(message.find('\n'), std::string::npos);
    };
    refused([](Scene& s) { s.terrain.heights[5] = NAN; }, "terrain height");
    refused([](Scene& s) { s.terrain.heights[5] = 9500; }, "beyond -500..9000 m");
    refused([](Scene& s) { s.terrain.reference_altitude = INFINITY; }, "reference altitude");
    refused([](Scene& s) { s.terrain.cell = 0; }, "beyond the limits");
    refused([](Scene& s) { s.terrain.cell = -20; }, "beyond the limits");
    refused([](Scene& s) { s.terrain.origin = {2e6, 0}; }, "beyond the limits");
    refused([](Scene& s) { s.terrain.nx = 1, s.terrain.ny = 42; }, "beyond the limits");
    // nx * ny beyond the node limit, whatever the heights say (the check comes before them).
    refused([](Scene& s) { s.terrain.nx = 1u << 16, s.terrain.ny = 1u << 11; }, "beyond the limits");
}

TEST(SceneIoTerrain, TheLimitPredicatesAgreeWithTheLoader) {
    EXPECT_TRUE(height_field_within_limit({0, 0}, 1, 8192, 8192));
    EXPECT_FALSE(height_field_within_limit({0, 0}, 1, 8193, 8192));
    EXPECT_FALSE(height_field_within_limit({0, 0}, NAN, 10, 10));
    EXPECT_FALSE(height_field_within_limit({9e5, 0}, 1000, 200, 10));  // its far corner beyond 1,000 km
    EXPECT_TRUE(altitude_within_limit(-430));
    EXPECT_FALSE(altitude_within_limit(NAN));
    EXPECT_FALSE(altitude_within_limit(9001));
}
