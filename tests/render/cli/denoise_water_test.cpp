// The denoiser at the water's edge: an island in the sea seen from above at 16 spp with
// --denoise. No pixel may come out far brighter, in any channel, than the raw image anywhere
// near it (the filter averages, it cannot create colour), and the sea keeps its mean colour.
// Dividing the sea's reflection by the body's dark albedo (0.01 in red) once painted magenta
// fringes along the coast: red 7x the raw neighbourhood's brightest.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>

#include "tests/render/test_exr.h"
#include "tests/test_support.h"

using namespace citygen::test;

TEST(WaterDenoise, NoColourAppearsThatTheRawImageDoesNotHaveNearby) {
    TempDir dir;
    const std::string scene = dir.file("island.scene"), out = dir.file("island.exr");
    const CommandResult parsed = parse_fixture_to("tests/data/map_island.osm", scene);
    ASSERT_EQ(parsed.exit_code, 0) << parsed.err;
    const CommandResult r = render(quoted(scene) + " -o " + quoted(out) +
                                   " --camera=-120,-120,50 --look-at=0,0,0 --fov 60 --width 96 --height 54"
                                   " --spp 16 --seed 4 --denoise --aovs id --quiet");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Exr exr = read_exr(out);
    ASSERT_EQ(exr.width, 96);
    const int raw = exr.channel("raw.R"), kind = exr.channel("id.kind");
    ASSERT_GE(raw, 0);
    ASSERT_GE(kind, 0);
    constexpr int kRadius = 3;  // a 7x7 neighbourhood
    constexpr float kLandCover = 7;
    double worst = 0;
    int over = 0, sea = 0;
    double mean_denoised[3] = {0, 0, 0}, mean_raw[3] = {0, 0, 0};
    for (int y = 0; y < exr.height; ++y)
        for (int x = 0; x < exr.width; ++x) {
            const int p = y * exr.width + x;
            for (int c = 0; c < 3; ++c) {
                float brightest = 0;
                for (int qy = std::max(0, y - kRadius); qy <= std::min(exr.height - 1, y + kRadius); ++qy)
                    for (int qx = std::max(0, x - kRadius); qx <= std::min(exr.width - 1, x + kRadius); ++qx)
                        brightest = std::max(brightest, exr.at(qy * exr.width + qx, raw + c));
                const double ratio = exr.at(p, c) / (brightest + 1e-3);
                worst = std::max(worst, ratio);
                over += ratio > 1.5;
            }
            if (exr.at(p, kind) == kLandCover) {
                ++sea;
                for (int c = 0; c < 3; ++c) mean_denoised[c] += exr.at(p, c), mean_raw[c] += exr.at(p, raw + c);
            }
        }
    std::printf("worst ratio to the raw neighbourhood's brightest %.2f, %d channel values over 1.5x\n", worst, over);
    EXPECT_EQ(over, 0) << "worst " << worst;
    ASSERT_GT(sea, exr.width * exr.height / 4);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean_denoised[c] / mean_raw[c], 1, 0.05) << "channel " << c;
}
