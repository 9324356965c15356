// Scene format 1.2: retaining walls round-trip; a scene without them has not a byte for them;
// a wall the loader cannot draw is refused with one line.
#include <gtest/gtest.h>

#include "common/error.h"
#include "common/scene_io.h"

using namespace citygen;

namespace {

Scene with_walls() {
    Scene s;
    s.header.bounds_min = {-50, -40};
    s.header.bounds_max = {50, 40};
    HeightField& t = s.terrain;
    t.origin = {-60, -50};
    t.cell = 20;
    t.nx = 7;
    t.ny = 6;
    t.heights.assign(t.nx * t.ny, 3.0f);
    RetainingWall a;
    a.osm = {OsmType::Way, 42};
    a.line = {{-10, 0}, {0, 5.5}, {10, 0}};
    a.height = 3.5;
    a.height_tagged = true;
    a.material = WallMaterial::Stone;
    RetainingWall b;
    b.osm = {OsmType::Way, 43};
    b.line = {{0, 0}, {5, 0}, {5, 5}, {0, 0}};
    b.height = 2;
    s.retaining_walls = {a, b};
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

TEST(SceneIoRetainingWalls, WallsRoundTrip) {
    const Scene s = with_walls();
    const std::vector<uint8_t> bytes = encode_scene(s);
    const Scene back = decode_scene(bytes.data(), bytes.size(), "walls.scene");
    ASSERT_EQ(back.retaining_walls.size(), 2u);
    const RetainingWall& a = back.retaining_walls[0];
    EXPECT_EQ(a.osm, (OsmRef{OsmType::Way, 42}));
    EXPECT_EQ(a.line, s.retaining_walls[0].line);
    EXPECT_DOUBLE_EQ(a.height, 3.5);
    EXPECT_TRUE(a.height_tagged);
    EXPECT_EQ(a.material, WallMaterial::Stone);
    const RetainingWall& b = back.retaining_walls[1];
    EXPECT_EQ(b.line.size(), 4u);
    EXPECT_FALSE(b.height_tagged);
    EXPECT_EQ(b.material, WallMaterial::Concrete);
    EXPECT_EQ(encode_scene(back), bytes);
}

TEST(SceneIoRetainingWalls, NoWallsNoBytes) {
    Scene s = with_walls();
    const size_t with = encode_scene(s).size();
    s.retaining_walls.clear();
    const std::vector<uint8_t> without = encode_scene(s);
    EXPECT_LT(without.size(), with);
    const Scene back = decode_scene(without.data(), without.size(), "none.scene");
    EXPECT_TRUE(back.retaining_walls.empty());
}

TEST(SceneIoRetainingWalls, TheLoaderRefusesAWallItCannotDraw) {
    Scene s = with_walls();
    s.retaining_walls[0].line = {{1, 1}};
    EXPECT_NE(refusal(s).find("retaining wall with fewer than 2 points"), std::string::npos) << refusal(s);
    s = with_walls();
    s.retaining_walls[1].height = 0;
    EXPECT_NE(refusal(s).find("retaining wall with zero height"), std::string::npos) << refusal(s);
    s = with_walls();
    s.retaining_walls[1].height = -1;
    EXPECT_NE(refusal(s).find("retaining wall height"), std::string::npos) << refusal(s);
    s = with_walls();
    s.retaining_walls[0].line[1] = {2e6, 0};
    EXPECT_NE(refusal(s).find("retaining wall line"), std::string::npos) << refusal(s);
}
