// The render program end to end: a real (small) parsed scene, every output format, the info
// options, and bad input giving one line on stderr, a non-zero exit and no output file.
#include <algorithm>
#include <cmath>
#include <filesystem>

#include <gtest/gtest.h>
#include <OpenImageIO/imageio.h>

#include "common/scene_io.h"
#include "render/scene/geometry_mode.h"
#include "tests/test_support.h"

using namespace citygen;
using namespace citygen::test;

namespace {


// The tiny roundabout fixture parsed once for all tests of this file.
class RenderCli : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        dir_ = new TempDir;
        const CommandResult r = parse_fixture_to("tests/data/tiny_roundabout.osm", scene());
        ASSERT_EQ(r.exit_code, 0) << r.err;
    }
    static void TearDownTestSuite() { delete dir_; }
    static std::string scene() { return dir_->file("tiny.scene"); }
    static std::string file(const std::string& name) { return dir_->file(name); }
    static TempDir* dir_;
};
TempDir* RenderCli::dir_ = nullptr;


}  // namespace

TEST_F(RenderCli, RealSceneDefaultViewShowsSkyAndGroundWithoutNanOrInf) {
    const std::string out = file("view.exr");
    const CommandResult r =
        render(quoted(scene()) + " -o " + quoted(out) + " --width 64 --height 36 --spp 2 --aovs depth,normal,albedo,id -q");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    auto in = OIIO::ImageInput::open(out);
    ASSERT_TRUE(in);
    const OIIO::ImageSpec spec = in->spec();
    ASSERT_EQ(spec.width, 64);
    ASSERT_EQ(spec.height, 36);
    ASSERT_EQ(spec.nchannels, 12);
    // EXR keeps its channels sorted by name, so look them up.
    auto channel = [&](const std::string& name) {
        const auto it = std::find(spec.channelnames.begin(), spec.channelnames.end(), name);
        return it == spec.channelnames.end() ? -1 : static_cast<int>(it - spec.channelnames.begin());
    };
    const int depth = channel("Z"), kind_channel = channel("id.kind");
    ASSERT_GE(depth, 0);
    ASSERT_GE(kind_channel, 0);
    for (const char* name : {"R", "G", "B", "N.X", "N.Y", "N.Z", "albedo.R", "albedo.G", "albedo.B", "id.index"})
        EXPECT_GE(channel(name), 0) << name;
    std::vector<float> pixels(64 * 36 * 12);
    ASSERT_TRUE(in->read_image(0, 0, 0, 12, OIIO::TypeDesc::FLOAT, pixels.data()));
    int sky = 0, ground = 0, buildings = 0, roads = 0;
    for (size_t p = 0; p < 64 * 36; ++p) {
        for (int c = 0; c < 12; ++c) ASSERT_TRUE(std::isfinite(pixels[12 * p + c])) << "pixel " << p;
        for (int c = 0; c < 3; ++c) EXPECT_GE(pixels[12 * p + c], 0);
        const auto kind = static_cast<ObjectKind>(static_cast<int>(pixels[12 * p + kind_channel]));
        sky += kind == ObjectKind::None;
        ground += kind == ObjectKind::Terrain;
        buildings += kind == ObjectKind::Building;
        roads += kind == ObjectKind::Road || kind == ObjectKind::Joint;
        if (kind == ObjectKind::None) EXPECT_EQ(pixels[12 * p + depth], 0.f);
        else EXPECT_GT(pixels[12 * p + depth], 0.f);
    }
    EXPECT_GT(sky, 0) << "the default view must show the sky";
    EXPECT_GT(ground, 0) << "the default view must show the ground";
    EXPECT_GT(buildings, 0);
    EXPECT_GT(roads, 0);
    // Sky rows are at the top: the first row is sky.
    EXPECT_EQ(pixels[kind_channel], 0.f);
}

TEST_F(RenderCli, PngJpegAndInfoLines) {
    for (const std::string name : {"a.png", "b.jpg", "c.JPEG"}) {
        const CommandResult r = render(quoted(scene()) + " -o " + quoted(file(name)) +
                                       " --width 32 --height 18 --spp 1 -q --time sunset --stats"
                                       " --print-memory-info --print-scene-geometry-info --print-scene-info");
        ASSERT_EQ(r.exit_code, 0) << r.err;
        auto in = OIIO::ImageInput::open(file(name));
        ASSERT_TRUE(in) << name;
        EXPECT_EQ(in->spec().width, 32);
        EXPECT_EQ(in->spec().nchannels, 3);
        for (const char* key : {"\ngeometry_bytes: ", "\npeak_rss_bytes: ", "\ntriangles: ", "\nrender_seconds: ",
                                "\nexposure_seconds: ", "\nrays_per_second: ", "\nbuildings: ", "\ntriangles_building: "})
            EXPECT_NE(("\n" + r.out).find(key), std::string::npos) << key;
    }
    for (const auto& entry : std::filesystem::directory_iterator(dir_->path()))
        EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
}

TEST_F(RenderCli, SameSeedGivesByteIdenticalFilesWithOneOrTwoThreads) {
    // Identical pixels are not enough: files must not carry the write time either (EXR did).
    for (const std::string ext : {".exr", ".png", ".jpg"}) {
        const std::string aovs = ext == ".exr" ? " --aovs depth,normal,albedo,id" : "";
        std::string bytes[2];
        for (int threads = 1; threads <= 2; ++threads) {
            const std::string out = file("threads" + std::to_string(threads) + ext);
            const CommandResult r = render(quoted(scene()) + " -o " + quoted(out) +
                                           " --width 40 --height 24 --spp 2 --seed 7 -q --threads " +
                                           std::to_string(threads) + aovs);
            ASSERT_EQ(r.exit_code, 0) << r.err;
            bytes[threads - 1] = read_text(out);
            auto in = OIIO::ImageInput::open(out);
            ASSERT_TRUE(in) << out;
            EXPECT_EQ(in->spec().find_attribute("DateTime"), nullptr) << out;
        }
        EXPECT_GT(bytes[0].size(), 100u) << ext;
        EXPECT_TRUE(bytes[0] == bytes[1]) << ext << " files differ between 1 and 2 threads";
    }
}

TEST_F(RenderCli, ExportPlyHasOneFacePerTriangleWithMaterials) {
    const CommandResult info = render(quoted(scene()) + " --print-scene-geometry-info --export-ply " +
                                      quoted(file("scene.ply")));
    ASSERT_EQ(info.exit_code, 0) << info.err;
    const size_t at = info.out.find("\ntriangles: ");
    ASSERT_NE(at, std::string::npos);
    const long triangles = std::stol(info.out.substr(at + 12));
    const std::string ply = read_text(file("scene.ply"));
    ASSERT_EQ(ply.rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u);
    EXPECT_NE(ply.find("element face " + std::to_string(triangles) + "\n"), std::string::npos);
    EXPECT_NE(ply.find("property ushort material_index\n"), std::string::npos);
    EXPECT_NE(ply.find("comment material 0 asphalt glossy "), std::string::npos);
    EXPECT_NE(ply.find("comment material 3 facade diffuse "), std::string::npos);
    const size_t header_end = ply.find("end_header\n") + 11;
    const size_t vertices_at = ply.find("element vertex ") + 15;
    const long vertices = std::stol(ply.substr(vertices_at));
    EXPECT_EQ(ply.size() - header_end, static_cast<size_t>(vertices * 12 + triangles * 15));
}

TEST_F(RenderCli, NotesACameraBelowTheGroundAndRendersAnyway) {
    // The fixture on a level field 30 m up (the cell triangles of a plane are the plane).
    Scene s = load_scene(scene());
    HeightField& f = s.terrain;
    f.cell = 10;
    f.origin = {std::floor(s.header.bounds_min.x / 10) * 10 - 20, std::floor(s.header.bounds_min.y / 10) * 10 - 20};
    f.nx = static_cast<uint32_t>((s.header.bounds_max.x - f.origin.x) / 10) + 3;
    f.ny = static_cast<uint32_t>((s.header.bounds_max.y - f.origin.y) / 10) + 3;
    f.heights.assign(static_cast<size_t>(f.nx) * f.ny, 30.0f);
    const std::string level = file("level.scene");
    save_scene(s, level);
    const std::string args = quoted(level) + " --width 32 --height 18 --spp 1 -q --look-at 50,0,0 -o ";
    const CommandResult below = render(args + quoted(file("below.png")) + " --camera 1,2,20");
    ASSERT_EQ(below.exit_code, 0) << below.err;
    EXPECT_EQ(below.err, "render: note: the camera is 10.0 m below the ground at 1.0,2.0\n");
    EXPECT_TRUE(std::filesystem::exists(file("below.png")));
    const CommandResult above = render(args + quoted(file("above.png")) + " --camera 1,2,31");
    ASSERT_EQ(above.exit_code, 0) << above.err;
    EXPECT_EQ(above.err, "");
}

TEST_F(RenderCli, BadInputGivesOneLineAndNoOutput) {
    write_text(file("corrupt.scene"), "this is not a scene file at all, just some bytes");
    const std::string existing = file("existing.png");
    write_text(existing, "previous contents\n");
    const std::string s = quoted(scene());
    const std::string o = " -o " + quoted(file("never.png"));
    const std::vector<std::string> cases = {
        quoted(file("missing.scene")) + o,
        quoted(file("corrupt.scene")) + " -o " + quoted(existing),
        quoted(file("corrupt.scene")) + o,
        s + " -o /nonexistent-dir/x.png",
        s + " -o " + quoted(file("image.bmp")),
        s + " -o " + quoted(file("noextension")),
        s + o + " --spp 0",
        s + o + " --width -3",
        s + o + " --height abc",
        s + o + " --fov 0",
        s + o + " --rr-prob 2",
        s + o + " --time noon",
        s + o + " --camera 1,2 --look-at 0,0,0",
        s + o + " --camera 1,2,3",
        s + o + " --geometry-roads=triangles",
        s + o + " --aovs depth,colour",
        s + o + " --no-such-option",
        s + o + " --lamp-power -1",
        s + o + " --lit-windows 1.5",
        s + o + " --fog nan",
        s + o + " --light-sampler foo",
        s + o + " --sun-elevation 200",
        s + o + " --exposure inf",
        s + o + " --lamp-kelvin 100",
        s + o + " --time night --fog -0.1",
        s,  // no output at all
    };
    for (const std::string& args : cases) {
        const CommandResult r = render(args + " -q");
        EXPECT_NE(r.exit_code, 0) << args;
        EXPECT_EQ(count_lines(r.err), 1) << args << "\n" << r.err;
        EXPECT_EQ(r.err.rfind("render: ", 0), 0u) << r.err;
    }
    EXPECT_FALSE(std::filesystem::exists(file("never.png")));
    EXPECT_EQ(read_text(existing), "previous contents\n");
    for (const auto& entry : std::filesystem::directory_iterator(dir_->path()))
        EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
}
