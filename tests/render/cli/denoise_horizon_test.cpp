// The denoiser where sky and ground meet: an island seen level across the sea at 16 spp with
// --denoise. The rows that hold the horizon keep their raw mean. The sky seen by part of a pixel
// was once left in the light the filter mixes, so horizon pixels whose centre sees the ground
// took their all-ground neighbours' light: a line across the image (0.9% off here, a dark line
// over Monaco's haze).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "tests/render/test_exr.h"
#include "tests/test_support.h"

using namespace citygen::test;

TEST(HorizonDenoise, TheRowsWhereSkyMeetsGroundKeepTheirMean) {
    TempDir dir;
    const std::string scene = dir.file("island.scene"), out = dir.file("island.exr");
    const CommandResult parsed = parse_fixture_to("tests/data/map_island.osm", scene);
    ASSERT_EQ(parsed.exit_code, 0) << parsed.err;
    const CommandResult r = render(quoted(scene) + " -o " + quoted(out) +
                                   " --camera=-150,-150,30 --look-at=0,0,20 --fov 40 --width 160 --height 90"
                                   " --spp 16 --seed 4 --denoise --aovs depth --quiet");
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const Exr exr = read_exr(out);
    ASSERT_EQ(exr.width, 160);
    const int raw = exr.channel("raw.R"), depth = exr.channel("Z");
    ASSERT_GE(raw, 0);
    ASSERT_GE(depth, 0);
    // The last row in which a pixel centre sees the sky (depth 0), and the rows just below it.
    int last_sky_row = -1;
    for (int y = 0; y < exr.height; ++y)
        for (int x = 0; x < exr.width; ++x)
            if (exr.at(y * exr.width + x, depth) == 0) last_sky_row = y;
    ASSERT_GT(last_sky_row, 0);
    ASSERT_LT(last_sky_row + 2, exr.height - 1) << "the view should show the horizon";
    auto luminance = [&](int p, int first) {
        return 0.2126 * exr.at(p, first) + 0.7152 * exr.at(p, first + 1) + 0.0722 * exr.at(p, first + 2);
    };
    double worst = 0;
    for (int y = last_sky_row; y <= last_sky_row + 2; ++y) {
        double denoised = 0, unfiltered = 0;
        for (int x = 0; x < exr.width; ++x) {
            denoised += luminance(y * exr.width + x, 0);
            unfiltered += luminance(y * exr.width + x, raw);
        }
        const double off = std::fabs(denoised / unfiltered - 1);
        std::printf("row %d: denoised mean %.5f, raw %.5f\n", y, denoised / exr.width, unfiltered / exr.width);
        worst = std::max(worst, off);
    }
    EXPECT_LT(worst, 0.003);
}
