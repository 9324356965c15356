// The defects of issue 8 in the scene model and its files: rings and values a scene may not
// hold, loading a directory, the simple-ring test at scale, where output may be written.
// The renderer's are in tests/render/hardening_test.cpp, the parser's in
// tests/osmparse/pipeline_hardening_test.cpp.
#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <cmath>
#include <cstring>
#include <random>

#include "common/error.h"
#include "common/output_target.h"
#include "common/scene_io.h"
#include "common/scene_limits.h"
#include "scene_generated.h"
#include "tests/test_scenes.h"
#include "tests/test_support.h"

using namespace citygen;
using namespace citygen::test;

namespace {

// Encodes (no checks) and decodes (all checks); returns the error message, empty when accepted.
std::string decode_error(const Scene& scene) {
    const std::vector<uint8_t> bytes = encode_scene(scene);
    try {
        decode_scene(bytes.data(), bytes.size(), "test.scene");
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

}  // namespace

TEST(Hardening, DecodeRefusesDegenerateRings) {
    Building b = box_building(0, 0, 10, 10);
    EXPECT_EQ(decode_error(scene_with(b)), "");
    b.outer = {{0, 0}, {1, 0}, {3, 0}, {2, 0}};
    EXPECT_NE(decode_error(scene_with(b)).find("zero area"), std::string::npos);
    b.outer = {{4, 4}, {4, 4}, {4, 4}};
    EXPECT_NE(decode_error(scene_with(b)).find("zero area"), std::string::npos);
    b.outer = {{0, 0}, {1, 0}};
    EXPECT_NE(decode_error(scene_with(b)).find("fewer than 3"), std::string::npos);
    b = box_building(0, 0, 10, 10);
    b.holes.push_back({{1, 1}, {2, 2}, {3, 3}});
    EXPECT_NE(decode_error(scene_with(b)).find("building hole has zero area"), std::string::npos);
}

// Defects 3 and 4: huge but finite values reached Embree and the geometry builders.
TEST(Hardening, DecodeRefusesValuesBeyondTheSceneLimits) {
    EXPECT_NE(decode_error(scene_with(box_building(1e30, 0, 1e30 + 1e25, 10))).find("from the origin"),
              std::string::npos);
    EXPECT_NE(decode_error(scene_with(box_building(0, 0, 10, 10, 1e6))).find("building height"), std::string::npos);
    EXPECT_NE(decode_error(scene_with(box_building(0, 0, 10, 10, -5))).find("building height"), std::string::npos);
    EXPECT_NE(decode_error(scene_with(box_building(0, 0, kMaxObjectExtent + 10, 10))).find("across"),
              std::string::npos);
    Building many = box_building(0, 0, 10, 10);
    many.outer.clear();
    for (size_t i = 0; i <= kMaxRingPoints; ++i) {
        const double a = 2 * kPi * static_cast<double>(i) / (kMaxRingPoints + 1);
        many.outer.push_back({100 * std::cos(a), 100 * std::sin(a)});
    }
    EXPECT_NE(decode_error(scene_with(many)).find("points (limit"), std::string::npos);
    many.outer.pop_back();
    EXPECT_EQ(decode_error(scene_with(many)), "");
    Scene lamp = scene_with(box_building(0, 0, 10, 10));
    lamp.lamps.push_back({});
    lamp.lamps.back().height = 1e9;
    EXPECT_NE(decode_error(lamp).find("lamp height"), std::string::npos);
}

// Found by scene_loader_fuzz under UBSan: FlatBuffers' verifier aligns a vector of structs to 4
// bytes only, but a Tree holds a 64-bit id. The tree list is moved to an offset that is 4 but
// not 8 bytes aligned, with the table pointing at it; everything else stays valid.
TEST(Hardening, DecodeRefusesAMisalignedTreeList) {
    Scene scene = scene_with(box_building(0, 0, 10, 10));
    scene.trees.push_back({});
    scene.trees.back().position = {20, 20};
    std::vector<uint8_t> bytes = encode_scene(scene);
    ASSERT_EQ(reinterpret_cast<uintptr_t>(bytes.data()) % 8, 0u);
    const fb::Scene* root = fb::GetScene(bytes.data());
    ASSERT_TRUE(root->trees() && root->trees()->size() == 1);
    const size_t field = static_cast<size_t>(reinterpret_cast<const uint8_t*>(root) - bytes.data()) +
                         reinterpret_cast<const flatbuffers::Table*>(root)->GetOptionalFieldOffset(fb::Scene::VT_TREES);
    const size_t old_data = static_cast<size_t>(reinterpret_cast<const uint8_t*>(root->trees()->Data()) - bytes.data());
    EXPECT_EQ(decode_error(scene), "");

    const size_t moved = (bytes.size() + 7) / 8 * 8;  // length prefix 8-aligned: the data after it is not
    bytes.resize(moved + 4 + sizeof(fb::Tree));
    const uint32_t count = 1, offset = static_cast<uint32_t>(moved - field);
    std::memcpy(bytes.data() + moved, &count, 4);
    std::memcpy(bytes.data() + moved + 4, bytes.data() + old_data, sizeof(fb::Tree));
    std::memcpy(bytes.data() + field, &offset, 4);
    ASSERT_NE(reinterpret_cast<uintptr_t>(fb::GetScene(bytes.data())->trees()->Data()) % alignof(fb::Tree), 0u);
    try {
        decode_scene(bytes.data(), bytes.size(), "test.scene");
        ADD_FAILURE() << "a misaligned tree list was accepted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("misaligned tree list"), std::string::npos) << e.what();
    }
}

TEST(Hardening, LoadingADirectorySaysSo) {
    TempDir dir;
    try {
        load_scene(dir.path());
        FAIL() << "loaded a directory";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("not a regular file"), std::string::npos) << e.what();
    }
}

// Defect 8: temp-file-and-rename replaced whatever the target was.
TEST(Hardening, OutputTargetsMustBeRegularFilesOrNewNames) {
    TempDir dir;
    const std::string input = dir.file("in.osm"), link = dir.file("link.scene"), fifo = dir.file("fifo.scene");
    write_text(input, "data");
    EXPECT_NO_THROW(check_output_target(dir.file("new.scene"), {input}));
    write_text(dir.file("old.scene"), "old");
    EXPECT_NO_THROW(check_output_target(dir.file("old.scene"), {input}));
    EXPECT_THROW(check_output_target(input, {input}), Error);
    ASSERT_EQ(::link(input.c_str(), dir.file("hard.osm").c_str()), 0);
    EXPECT_THROW(check_output_target(dir.file("hard.osm"), {input}), Error);
    ASSERT_EQ(::symlink(dir.file("old.scene").c_str(), link.c_str()), 0);
    EXPECT_THROW(check_output_target(link, {}), Error);
    ASSERT_EQ(::mkfifo(fifo.c_str(), 0644), 0);
    EXPECT_THROW(check_output_target(fifo, {}), Error);
    EXPECT_THROW(check_output_target(dir.path(), {}), Error);
    EXPECT_THROW(check_output_target("/dev/null", {}), Error);
    EXPECT_THROW(check_output_target(dir.file("missing/x.scene"), {}), Error);
    EXPECT_THROW(write_file_atomically(fifo, "x", 1), Error);
    EXPECT_EQ(read_text(dir.file("old.scene")), "old");
}

// The check runs while the bytes are written: a check that throws leaves the old file as it was
// and no temporary file beside it; one that returns lets the new bytes replace the old.
TEST(Hardening, AFailedCheckWhileWritingLeavesTheOldFile) {
    TempDir dir;
    const std::string target = dir.file("out.scene");
    write_text(target, "old");
    const std::string bytes(1 << 20, 'n');
    bool checked = false;
    EXPECT_THROW(write_file_atomically(target, bytes.data(), bytes.size(),
                                       [&] {
                                           checked = true;
                                           throw Error("refused");
                                       }),
                 Error);
    EXPECT_TRUE(checked);
    EXPECT_EQ(read_text(target), "old");
    size_t files = 0;
    for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path())) ++files;
    EXPECT_EQ(files, 1u);  // no temporary file left

    write_file_atomically(target, bytes.data(), bytes.size(), [&] {});
    EXPECT_EQ(read_text(target), bytes);
}
