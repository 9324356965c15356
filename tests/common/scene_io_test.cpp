// Scene file round trip and the loader's refusal of bad bytes.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>

#include "common/error.h"
#include "common/scene_io.h"
#include "scene_generated.h"

using namespace citygen;

namespace {

Scene small_scene() {
    Scene s;
    s.header.generator = "test";
    s.header.origin_lat = 43.7;
    s.header.origin_lon = 7.4;
    s.header.projection = "transverse-mercator";
    s.header.options = {{"seed", "1"}};
    Building b;
    b.osm = {OsmType::Way, 42};
    b.outer = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
    b.holes = {{{2, 2}, {2, 4}, {4, 4}, {4, 2}}};
    b.height = 12;
    s.buildings.push_back(b);
    RoadEdge r;
    r.osm = {OsmType::Way, 7};
    r.centreline = {{0, -5}, {10, -5}};
    r.quad = {{0, -7}, {10, -7}, {10, -3}, {0, -3}};
    r.width = 4;
    r.to_joint = 0;
    s.roads.push_back(r);
    Joint j;
    j.osm = {OsmType::Node, 3};
    j.polygon = {{10, -7}, {12, -7}, {12, -3}, {10, -3}};
    j.edges = {0};
    s.joints.push_back(j);
    Lamp l;
    l.osm = {OsmType::Node, 9};
    l.position = {1, 2, 0};
    s.lamps.push_back(l);
    return s;
}

std::string temp_path(const char* name) { return ::testing::TempDir() + name; }

std::vector<uint8_t> read_all(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string load_error(const std::vector<uint8_t>& bytes) {
    try {
        decode_scene(bytes.data(), bytes.size(), "x.scene");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(SceneIo, RoundTripKeepsEverything) {
    const Scene s = small_scene();
    const std::vector<uint8_t> bytes = encode_scene(s);
    const Scene t = decode_scene(bytes.data(), bytes.size(), "mem");
    ASSERT_EQ(t.buildings.size(), 1u);
    EXPECT_EQ(t.buildings[0].osm.id, 42);
    EXPECT_EQ(t.buildings[0].holes.size(), 1u);
    EXPECT_FLOAT_EQ(t.buildings[0].height, 12);
    ASSERT_EQ(t.roads.size(), 1u);
    EXPECT_EQ(t.roads[0].to_joint, 0);
    EXPECT_EQ(t.joints[0].edges, std::vector<uint32_t>{0});
    EXPECT_EQ(t.lamps[0].position.y, 2);
    EXPECT_EQ(t.header.options, s.header.options);
    EXPECT_EQ(encode_scene(t), bytes) << "re-encoding must give identical bytes";
}

TEST(SceneIo, RejectsWrongIdentifier) {
    std::vector<uint8_t> bytes = encode_scene(small_scene());
    bytes[4] = 'X';
    EXPECT_NE(load_error(bytes).find("wrong file identifier"), std::string::npos);
}

TEST(SceneIo, RejectsTruncatedFile) {
    std::vector<uint8_t> bytes = encode_scene(small_scene());
    bytes.resize(bytes.size() / 2);
    EXPECT_NE(load_error(bytes).find("x.scene: corrupt or truncated"), std::string::npos);
}

TEST(SceneIo, RejectsEmptyFile) {
    EXPECT_NE(load_error({}).find("empty file"), std::string::npos);
}

TEST(SceneIo, RejectsNewerMajorVersion) {
    Scene s = small_scene();
    s.header.format_major = kSceneFormatMajor + 1;
    EXPECT_NE(load_error(encode_scene(s)).find("newer than this program reads"), std::string::npos);
}

TEST(SceneIo, RejectsIndexOutOfRange) {
    Scene s = small_scene();
    s.roads[0].to_joint = 5;
    EXPECT_NE(load_error(encode_scene(s)).find("out of range"), std::string::npos);
    s = small_scene();
    s.joints[0].edges = {3};
    EXPECT_NE(load_error(encode_scene(s)).find("out of range"), std::string::npos);
}

TEST(SceneIo, RejectsNonFiniteCoordinate) {
    Scene s = small_scene();
    s.buildings[0].outer[1].x = NAN;
    EXPECT_NE(load_error(encode_scene(s)).find("non-finite coordinate"), std::string::npos);
}

TEST(SceneIo, RandomCorruptionNeverCrashes) {
    const std::vector<uint8_t> good = encode_scene(small_scene());
    for (size_t i = 8; i < good.size(); ++i) {
        std::vector<uint8_t> bad = good;
        bad[i] ^= 0xA5;
        try {
            decode_scene(bad.data(), bad.size(), "x");
        } catch (const Error&) {
        }
    }
    SUCCEED() << "every corrupted byte was either rejected or decoded safely";
}

TEST(SceneIo, SaveIsAtomicAndLeavesNoPartialFile) {
    const std::string path = temp_path("citygen_atomic.scene");
    save_scene(small_scene(), path);
    const std::vector<uint8_t> before = read_all(path);
    ASSERT_FALSE(before.empty());
    // A directory that does not exist: the write fails, nothing is left behind.
    EXPECT_THROW(save_scene(small_scene(), temp_path("no_such_dir/x.scene")), Error);
    EXPECT_EQ(read_all(path), before);
    std::remove(path.c_str());
}

TEST(SceneIo, LoadMissingFileNamesIt) {
    try {
        load_scene("/nonexistent/city.scene");
        FAIL() << "no error";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent/city.scene"), std::string::npos);
    }
}

// SceneEncoder, as osmparse uses it: the header written before the bounds are known, the
// buildings one by one, then the rest with each part freed once encoded.
TEST(SceneIo, EncoderPartByPartGivesEncodeScenesBytes) {
    Scene s = small_scene();
    s.header.bounds_min = {-1, -7};
    s.header.bounds_max = {12, 10};
    s.buildings.push_back(s.buildings.front());
    s.buildings.back().osm.id = 43;
    s.buildings.back().roof_faces = {{{{0, 0, 12}, {10, 0, 12}, {5, 5, 15}}, RoofFaceKind::Roof}};
    s.terrain.origin = {-10, -10};
    s.terrain.cell = 10;
    s.terrain.nx = s.terrain.ny = 3;
    s.terrain.heights = {0, 1, 2, 3, 4, 5, 6, 7, 8};
    RetainingWall wall;
    wall.line = {{0, 0}, {5, 1}};
    wall.height = 2;
    s.retaining_walls = {wall};
    const std::vector<uint8_t> whole = encode_scene(s);

    SceneHeader early = s.header;
    early.bounds_min = early.bounds_max = {0, 0};  // not known yet when the header is written
    SceneEncoder encoder(early, 64);               // a short reserve: the builder grows
    for (const Building& b : s.buildings) encoder.add_building(b);
    Scene rest = s;
    encoder.finish_releasing(rest);
    EXPECT_EQ(std::vector<uint8_t>(encoder.data(), encoder.data() + encoder.size()), whole);
    EXPECT_TRUE(rest.roads.empty() && rest.joints.empty() && rest.lamps.empty() && rest.terrain.heights.empty() &&
                rest.retaining_walls.empty())
        << "encoded parts are freed";

    const Scene t = decode_scene(encoder.data(), encoder.size(), "mem");
    EXPECT_FLOAT_EQ(t.header.bounds_min.y, -7);
    EXPECT_FLOAT_EQ(t.header.bounds_max.x, 12);
    ASSERT_EQ(t.buildings.size(), 2u);
    EXPECT_EQ(t.buildings[1].roof_faces.size(), 1u);
    EXPECT_EQ(t.terrain.heights, s.terrain.heights);
    EXPECT_EQ(t.retaining_walls.size(), 1u);
}
