// Production options end to end: regions that tile the full frame exactly, animation frames that
// equal a lone render of the same frame, time-limited renders that equal the fixed-spp render of
// the passes reached, the denoiser's EXR layers, and bad input (one line, non-zero exit, no files).
#include <algorithm>
#include <filesystem>
#include <vector>

#include <gtest/gtest.h>
#include <OpenImageIO/imageio.h>

#include "tests/test_support.h"

using namespace citygen::test;

namespace {


struct Image {
    int width = 0, height = 0, channels = 0;
    std::vector<std::string> names;
    std::vector<float> pixels;
    float at(int x, int y, int c) const { return pixels[(static_cast<size_t>(y) * width + x) * channels + c]; }
};

Image read_image(const std::string& path) {
    Image image;
    auto in = OIIO::ImageInput::open(path);
    if (!in) return image;
    image.width = in->spec().width;
    image.height = in->spec().height;
    image.channels = in->spec().nchannels;
    image.names = in->spec().channelnames;
    image.pixels.resize(static_cast<size_t>(image.width) * image.height * image.channels);
    in->read_image(0, 0, 0, image.channels, OIIO::TypeDesc::FLOAT, image.pixels.data());
    return image;
}


class ProductionCli : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        dir_ = new TempDir;
        const CommandResult r = parse_fixture_to("tests/data/tiny_roundabout.osm", scene());
        ASSERT_EQ(r.exit_code, 0) << r.err;
        write_text(path_file(), "# a short fly-by of the roundabout\n"
                                "time,x,y,z,look_x,look_y,look_z,fov\n"
                                "0, -60,-60,30, 0,0,0, 50\n"
                                "1, 0,-80,20, 0,0,5, 45\n"
                                "2, 60,-40,15, 0,0,5, 40\n");
    }
    static void TearDownTestSuite() { delete dir_; }
    static std::string scene() { return dir_->file("tiny.scene"); }
    static std::string path_file() { return dir_->file("path.csv"); }
    static std::string file(const std::string& name) { return dir_->file(name); }
    static std::string small() { return " --width 48 --height 30 --spp 2 -q"; }
    static TempDir* dir_;
};
TempDir* ProductionCli::dir_ = nullptr;

}  // namespace

TEST_F(ProductionCli, RegionsTileTheFullFrameExactly) {
    // Uneven tiles (the frame does not split evenly), PNG and EXR. The denoised EXR frame is wide
    // enough that a tile's 10-pixel filter margin does not reach across the whole frame, so the
    // margin itself is what makes its tiles match.
    struct Case {
        std::string ext, options;
        int width, height, split_x, split_y;
    };
    for (const Case& k : {Case{".png", "", 48, 30, 17, 11}, Case{".exr", " --denoise --aovs depth,id", 112, 72, 70, 40}}) {
        const std::string size = " --width " + std::to_string(k.width) + " --height " + std::to_string(k.height) +
                                 " --spp 2 -q" + k.options;
        const std::string full_path = file("full" + k.ext);
        ASSERT_EQ(render(quoted(scene()) + " -o " + quoted(full_path) + size).exit_code, 0);
        const Image full = read_image(full_path);
        ASSERT_EQ(full.width, k.width);
        const int xs[] = {0, k.split_x, k.width}, ys[] = {0, k.split_y, k.height};
        int tiles = 0;
        for (int ty = 0; ty < 2; ++ty)
            for (int tx = 0; tx < 2; ++tx) {
                const std::string region = std::to_string(xs[tx]) + "," + std::to_string(ys[ty]) + "," +
                                           std::to_string(xs[tx + 1]) + "," + std::to_string(ys[ty + 1]);
                const std::string tile_path = file("tile" + std::to_string(tiles++) + k.ext);
                const CommandResult r = render(quoted(scene()) + " -o " + quoted(tile_path) + size + " --region " + region);
                ASSERT_EQ(r.exit_code, 0) << r.err;
                const Image tile = read_image(tile_path);
                ASSERT_EQ(tile.width, xs[tx + 1] - xs[tx]) << k.options;
                ASSERT_EQ(tile.height, ys[ty + 1] - ys[ty]) << k.options;
                ASSERT_EQ(tile.names, full.names) << k.options;
                for (int y = 0; y < tile.height; ++y)
                    for (int x = 0; x < tile.width; ++x)
                        for (int c = 0; c < tile.channels; ++c)
                            ASSERT_EQ(tile.at(x, y, c), full.at(xs[tx] + x, ys[ty] + y, c))
                                << k.options << " region " << region << " pixel " << x << "," << y << " channel " << c;
            }
    }
}

TEST_F(ProductionCli, AnimationFrameAloneEqualsThatFrameOfTheRunAndAStillOfItsKeyframe) {
    const CommandResult run =
        render(quoted(scene()) + " --camera-path " + quoted(path_file()) + " --fps 2 -o " + quoted(file("run_%03d.png")) +
               " --width 48 --height 30 --spp 2");
    ASSERT_EQ(run.exit_code, 0) << run.err;
    // Frames 0..4 at 2 fps cover keys 0..2 s; one progress line per frame with the run's ETA.
    for (int n = 0; n <= 4; ++n) {
        char name[32];
        std::snprintf(name, sizeof name, "run_%03d.png", n);
        EXPECT_TRUE(std::filesystem::exists(file(name))) << name;
    }
    EXPECT_FALSE(std::filesystem::exists(file("run_005.png")));
    EXPECT_NE(run.err.find("frame 5 of 5"), std::string::npos) << run.err;
    EXPECT_NE(run.err.find("ETA"), std::string::npos) << run.err;

    const CommandResult alone = render(quoted(scene()) + " --camera-path " + quoted(path_file()) +
                                       " --fps 2 --frames 3-3 -o " + quoted(file("alone_%03d.png")) + small());
    ASSERT_EQ(alone.exit_code, 0) << alone.err;
    EXPECT_EQ(read_text(file("alone_003.png")), read_text(file("run_003.png")));
    EXPECT_FALSE(std::filesystem::exists(file("alone_002.png")));
    EXPECT_NE(read_text(file("run_002.png")), read_text(file("run_003.png")));

    // Frame 2 (t = 1 s) is keyframe 1: the same as a still from that camera.
    ASSERT_EQ(render(quoted(scene()) + " --camera 0,-80,20 --look-at 0,0,5 --fov 45 -o " + quoted(file("key1.png")) +
                     small())
                  .exit_code,
              0);
    EXPECT_EQ(read_text(file("key1.png")), read_text(file("run_002.png")));
}

TEST_F(ProductionCli, OrbitFramesAreIndependentAndTurn) {
    ASSERT_EQ(render(quoted(scene()) + " --orbit --orbit-seconds 4 --fps 1 -o " + quoted(file("orbit_%d.png")) + small())
                  .exit_code,
              0);
    for (int n = 0; n < 4; ++n) EXPECT_TRUE(std::filesystem::exists(file("orbit_" + std::to_string(n) + ".png")));
    EXPECT_FALSE(std::filesystem::exists(file("orbit_4.png"))) << "frame 4 would repeat frame 0";
    EXPECT_NE(read_text(file("orbit_0.png")), read_text(file("orbit_2.png")));
    ASSERT_EQ(render(quoted(scene()) + " --orbit --orbit-seconds 4 --fps 1 --frames 2 -o " +
                     quoted(file("orbit2_%d.png")) + small())
                  .exit_code,
              0);
    EXPECT_EQ(read_text(file("orbit2_2.png")), read_text(file("orbit_2.png")));
    // Frame 0 of the orbit is the automatic view.
    ASSERT_EQ(render(quoted(scene()) + " -o " + quoted(file("auto.png")) + small()).exit_code, 0);
    const Image a = read_image(file("auto.png")), b = read_image(file("orbit_0.png"));
    ASSERT_EQ(a.pixels.size(), b.pixels.size());
    double difference = 0;
    for (size_t i = 0; i < a.pixels.size(); ++i) difference += std::abs(a.pixels[i] - b.pixels[i]);
    EXPECT_LT(difference / a.pixels.size(), 0.02);
}

TEST_F(ProductionCli, TimeLimitEqualsTheFixedRenderOfThePassesReached) {
    const CommandResult limited = render(quoted(scene()) + " -o " + quoted(file("limited.exr")) +
                                         " --width 48 --height 30 --time-limit 0.3 --stats");
    ASSERT_EQ(limited.exit_code, 0) << limited.err;
    const size_t at = limited.out.find("spp: ");
    ASSERT_NE(at, std::string::npos) << limited.out;
    const int passes = std::stoi(limited.out.substr(at + 5));
    EXPECT_GE(passes, 1);
    EXPECT_NE(limited.err.find("passes"), std::string::npos) << limited.err;
    ASSERT_EQ(render(quoted(scene()) + " -o " + quoted(file("fixed.exr")) + " --width 48 --height 30 -q --spp " +
                     std::to_string(passes))
                  .exit_code,
              0);
    EXPECT_EQ(read_text(file("limited.exr")), read_text(file("fixed.exr"))) << passes << " passes";
    // --spp caps the passes of a generous time limit.
    const CommandResult capped = render(quoted(scene()) + " -o " + quoted(file("capped.png")) +
                                        " --width 48 --height 30 --time-limit 60 --spp 3 -q --stats");
    ASSERT_EQ(capped.exit_code, 0) << capped.err;
    EXPECT_NE(capped.out.find("spp: 3\n"), std::string::npos) << capped.out;
}

TEST_F(ProductionCli, DenoisedExrKeepsTheRawImageAsALayer) {
    ASSERT_EQ(render(quoted(scene()) + " -o " + quoted(file("raw.exr")) + small()).exit_code, 0);
    ASSERT_EQ(render(quoted(scene()) + " -o " + quoted(file("denoised.exr")) + small() + " --denoise").exit_code, 0);
    const Image raw = read_image(file("raw.exr")), denoised = read_image(file("denoised.exr"));
    ASSERT_EQ(denoised.channels, 6);
    auto channel = [&](const std::string& name) {
        return static_cast<int>(std::find(denoised.names.begin(), denoised.names.end(), name) - denoised.names.begin());
    };
    double changed = 0;
    for (int y = 0; y < raw.height; ++y)
        for (int x = 0; x < raw.width; ++x)
            for (int c = 0; c < 3; ++c) {
                const char* rgb[] = {"R", "G", "B"};
                ASSERT_EQ(denoised.at(x, y, channel(std::string("raw.") + rgb[c])), raw.at(x, y, c));
                changed += std::abs(denoised.at(x, y, channel(rgb[c])) - raw.at(x, y, c));
            }
    EXPECT_GT(changed, 0) << "the filter changed nothing";
}

TEST_F(ProductionCli, BadProductionInputGivesOneLineAndWritesNothing) {
    write_text(file("bad_fields.csv"), "0,1,2,3,4,5,6,50\n1,1,2,3,4,5\n");
    write_text(file("bad_number.csv"), "0,1,2,3,4,5,6,50\n1,1,2,x,4,5,6,50\n");
    const std::string s = quoted(scene());
    const std::string pattern = " -o " + quoted(file("never_%04d.png"));
    const std::string path = " --camera-path " + quoted(path_file());
    const std::vector<std::string> cases = {
        s + pattern + " --camera-path " + quoted(file("missing.csv")),
        s + pattern + " --camera-path " + quoted(file("bad_fields.csv")),
        s + pattern + " --camera-path " + quoted(file("bad_number.csv")),
        s + pattern + path + " --frames 3-1",
        s + pattern + path + " --frames 0-500",
        s + pattern + " --orbit --frames 0-1000",
        s + pattern + path + " --orbit",
        s + pattern + path + " --camera 1,2,3 --look-at 0,0,0",
        s + " -o " + quoted(file("never.png")) + path,                      // no frame number
        s + " -o " + quoted(file("never_%d_%d.png")) + path,                // two
        s + " -o /nonexistent-dir/out_%04d.png" + path,                     // unwritable
        s + " -o " + quoted(file("never.png")) + " --frames 1-2",           // frames of nothing
        s + " -o " + quoted(file("never.png")) + " --region 0,0,2000,10",   // outside the frame
        s + " -o " + quoted(file("never.png")) + " --region 10,10,10,20",   // empty
        s + " -o " + quoted(file("never.png")) + " --region 1,2,3",
        s + " -o " + quoted(file("never.png")) + " --time-limit -1",
        s + " -o " + quoted(file("never.png")) + " --time-limit nan",
        s + pattern + " --orbit --fps nan",
        s + pattern + " --orbit --orbit-seconds inf",
    };
    for (const std::string& args : cases) {
        const CommandResult r = render(args + " --width 48 --height 30 --spp 1 -q");
        EXPECT_NE(r.exit_code, 0) << args;
        EXPECT_EQ(count_lines(r.err), 1) << args << "\n" << r.err;
        EXPECT_EQ(r.err.rfind("render: ", 0), 0u) << r.err;
    }
    for (const auto& entry : std::filesystem::directory_iterator(dir_->path())) {
        EXPECT_EQ(entry.path().filename().string().find("never"), std::string::npos) << entry.path();
        EXPECT_EQ(entry.path().string().find(".tmp"), std::string::npos) << entry.path();
    }
}
