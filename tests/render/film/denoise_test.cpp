// The regression denoiser on synthetic films: a constant image stays exactly constant, no light
// crosses a normal edge or a step in the light, noise goes down on a flat surface, and the
// threads do not change a bit.
#include <algorithm>
#include <cmath>
#include <vector>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "common/rng.h"
#include "render/film/denoise.h"

using namespace citygen;

namespace {

// A 64x48 film of one flat wall (normal +z, depth 10, albedo 0.5, building 1) with the given colour.
Film flat_film(float r, float g, float b) {
    Film film;
    film.width = 64;
    film.height = 48;
    const size_t n = 64 * 48;
    film.guide_depth.assign(n, 10.f);
    film.guide_variance.assign(n, 0.f);
    film.object_kind.assign(n, 1.f);
    film.object_index.assign(n, 1.f);
    film.guide_normal.assign(3 * n, 0.f);
    film.guide_albedo.assign(3 * n, 0.5f);
    film.rgb.resize(3 * n);
    for (size_t i = 0; i < n; ++i) {
        film.guide_normal[3 * i + 2] = 1;
        film.rgb[3 * i] = r, film.rgb[3 * i + 1] = g, film.rgb[3 * i + 2] = b;
    }
    return film;
}

// Uniform noise of +-amount/2 relative, and the variance of it that a renderer would report.
void add_noise(Film& film, uint64_t seed, double amount) {
    Rng rng(seed);
    for (size_t i = 0; i < film.guide_variance.size(); ++i) {
        const double value = film.rgb[3 * i];
        for (int c = 0; c < 3; ++c)
            film.rgb[3 * i + c] = static_cast<float>(film.rgb[3 * i + c] * (1 + amount * (rng.next_double() - 0.5)));
        film.guide_variance[i] = static_cast<float>(value * value * amount * amount / 12);
    }
}

double mean_abs_error(const Film& film, int x0, int x1, float r) {
    double sum = 0;
    int count = 0;
    for (int y = 0; y < film.height; ++y)
        for (int x = x0; x < x1; ++x, ++count) sum += std::abs(film.rgb[3 * (y * film.width + x)] - r);
    return sum / count;
}

}  // namespace

TEST(Denoise, ConstantImageStaysExactlyConstant) {
    for (float value : {0.f, 0.123456f, 3.7f, 1234.5f}) {
        Film film = flat_film(value, value * 0.5f, value * 0.25f);
        // Guides that vary (depth ramp, two objects) must not matter for a constant colour.
        for (int x = 0; x < film.width; ++x) film.guide_depth[x] = 5.f + x;
        for (size_t i = 0; i < film.guide_variance.size(); ++i) film.guide_variance[i] = 0.01f * (i % 5);
        for (size_t i = 0; i < film.object_index.size(); i += 7) film.object_index[i] = 2;
        const std::vector<float> before = film.rgb;
        denoise(film, 1.0);
        EXPECT_EQ(film.rgb, before) << value;
        EXPECT_EQ(film.raw_rgb, before);
    }
}

TEST(Denoise, NoLightCrossesANormalEdgeOrAStepInTheLight) {
    // Left half: dark wall; right half: bright, either another object with the same guides (only
    // the light tells them apart) or the same object facing another way. The left half must come
    // out as if the right half were not there, but for the column beside the edge, whose 3x3
    // patches see it.
    for (const bool normal_edge : {false, true}) {
        Film film = flat_film(0.1f, 0.1f, 0.1f);
        add_noise(film, 3, 0.8);
        Film brighter = film;
        for (int y = 0; y < film.height; ++y)
            for (int x = 32; x < 64; ++x) {
                const size_t i = y * 64 + x;
                for (Film* f : {&film, &brighter}) {
                    if (normal_edge) {
                        f->guide_normal[3 * i + 0] = 1;
                        f->guide_normal[3 * i + 2] = 0;
                    } else {
                        f->object_index[i] = 2;
                    }
                }
                for (int c = 0; c < 3; ++c) {
                    film.rgb[3 * i + c] = 5.f;
                    brighter.rgb[3 * i + c] = 50.f;
                }
                film.guide_variance[i] = 1.f;
                brighter.guide_variance[i] = 100.f;
            }
        denoise(film, 1.0);
        denoise(brighter, 1.0);
        for (int y = 0; y < 48; ++y)
            for (int x = 0; x < 31; ++x)
                for (int c = 0; c < 3; ++c)
                    ASSERT_EQ(film.rgb[3 * (y * 64 + x) + c], brighter.rgb[3 * (y * 64 + x) + c])
                        << (normal_edge ? "normal" : "light") << " edge, pixel " << x << "," << y;
        EXPECT_LT(mean_abs_error(film, 0, 32, 0.1f), 0.01) << "the dark side stays dark";
        EXPECT_LT(mean_abs_error(brighter, 0, 32, 0.1f), 0.01) << "the dark side stays dark";
    }
}

TEST(Denoise, ReducesNoiseOnAFlatWallAndIgnoresTheThreadCount) {
    Film film = flat_film(0.4f, 0.4f, 0.4f);
    add_noise(film, 11, 1.0);
    const double before = mean_abs_error(film, 0, 64, 0.4f);
    Film one_thread = film;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        denoise(one_thread, 1.0);
    }
    denoise(film, 1.0);
    EXPECT_EQ(film.rgb, one_thread.rgb);
    EXPECT_LT(mean_abs_error(film, 0, 64, 0.4f), 0.25 * before);
}

TEST(Denoise, DoesNotSpreadAFireflyIntoABlob) {
    // One pixel of a noisy wall caught a rare bright path: 250 times the wall, and a variance that
    // says so. Pixels beyond its own 3x3 patch must not take it into their fits.
    Film film = flat_film(0.2f, 0.2f, 0.2f);
    add_noise(film, 17, 0.8);
    const size_t firefly = 24 * 64 + 32;
    for (int c = 0; c < 3; ++c) film.rgb[3 * firefly + c] = 50.f;
    film.guide_variance[firefly] = 50.f * 50.f;
    denoise(film, 1.0);
    double worst = 0;
    for (int y = 0; y < 48; ++y)
        for (int x = 0; x < 64; ++x)
            if (std::max(std::abs(x - 32), std::abs(y - 24)) >= 2)
                worst = std::max(worst, std::abs(film.rgb[3 * (y * 64 + x)] - 0.2));
    EXPECT_LT(worst, 0.1);
}

TEST(Denoise, LeavesTheSkyAlone) {
    // Sky pixels (object kind 0) have no path noise: stars must stay single sharp pixels.
    Film film = flat_film(0.01f, 0.01f, 0.02f);
    std::fill(film.object_kind.begin(), film.object_kind.end(), 0.f);
    std::fill(film.guide_albedo.begin(), film.guide_albedo.end(), 0.f);
    for (int c = 0; c < 3; ++c) film.rgb[3 * (20 * 64 + 30) + c] = 3.f;
    const std::vector<float> before = film.rgb;
    denoise(film, 1.0);
    EXPECT_EQ(film.rgb, before);
}

TEST(Denoise, NeedsTheGuides) {
    Film film = flat_film(1, 1, 1);
    film.guide_depth.clear();
    EXPECT_THROW(denoise(film, 1.0), std::exception);
}

TEST(Denoise, AddsTheDirectLightBackUnfiltered) {
    // A lit window (one bright pixel) and a sunlit band on a noisy wall, both known to the
    // direct-light guide: they come back exactly where they were, and the wall around them is
    // filtered as if they were not there, to about its remaining noise (the direct light is one
    // of the fit's guides, so the fit is not quite the same).
    Film film = flat_film(0.2f, 0.2f, 0.2f);
    add_noise(film, 5, 0.8);
    film.guide_direct.assign(film.rgb.size(), 0.f);
    Film lit = film;
    auto add_direct = [&](int x, int y, float value) {
        for (int c = 0; c < 3; ++c) {
            lit.guide_direct[3 * (y * 64 + x) + c] = value;
            lit.rgb[3 * (y * 64 + x) + c] += value;
        }
    };
    add_direct(30, 20, 40.f);
    for (int y = 0; y < 48; ++y)
        for (int x = 40; x < 48; ++x) add_direct(x, y, 2.f);
    denoise(film, 1.0);
    denoise(lit, 1.0);
    for (size_t k = 0; k < film.rgb.size(); ++k)
        ASSERT_NEAR(lit.rgb[k], film.rgb[k] + lit.guide_direct[k], 0.03f + 1e-3f * lit.guide_direct[k]) << k / 3;
    EXPECT_LT(mean_abs_error(film, 0, 64, 0.2f), 0.02) << "the wall is still filtered";
    for (size_t k = 0; k < lit.rgb.size(); ++k) lit.rgb[k] -= lit.guide_direct[k];
    EXPECT_LT(mean_abs_error(lit, 0, 64, 0.2f), 0.02) << "the wall is still filtered";
}

TEST(Denoise, CancelsWhereTheSamplesFellOnTheDirectLight) {
    // A lamp globe covers part of a few pixels: the samples saw more or less of it than the
    // guide's fixed grid. With the direct light along the samples known, that difference is
    // not noise to spread: the result equals the one from samples that saw exactly the grid's
    // share, and the globe comes back at the grid's value.
    Film exact = flat_film(0.2f, 0.2f, 0.2f);
    add_noise(exact, 7, 0.8);
    exact.guide_direct.assign(exact.rgb.size(), 0.f);
    for (int x = 20; x < 24; ++x)
        for (int c = 0; c < 3; ++c) {
            const size_t k = 3 * (10 * 64 + x) + c;
            exact.guide_direct[k] = 30.f;
            exact.rgb[k] += 30.f;
        }
    exact.guide_sample_direct = exact.guide_direct;
    Film sampled = exact;
    Rng rng(9);
    for (int x = 20; x < 24; ++x) {
        const float seen = static_cast<float>(60 * rng.next_double());  // 0..60 instead of 30
        for (int c = 0; c < 3; ++c) {
            const size_t k = 3 * (10 * 64 + x) + c;
            sampled.guide_sample_direct[k] = seen;
            sampled.rgb[k] += seen - 30.f;
        }
    }
    denoise(exact, 1.0);
    denoise(sampled, 1.0);
    for (size_t k = 0; k < exact.rgb.size(); ++k) ASSERT_NEAR(sampled.rgb[k], exact.rgb[k], 1e-4f) << k / 3;
    EXPECT_NE(sampled.raw_rgb, exact.raw_rgb);
}

TEST(Denoise, KeepsAStepThatNoGuideKnows) {
    // The edge of a soft shadow on one flat wall: the light steps from 0.2 to 0.3 at x = 32 and
    // only the luminance tells. The noise goes, the step stays: it climbs most of the way within
    // three pixels and each side keeps its level more than three pixels from it. Without the luminance weights the fit
    // would spread it over the whole window.
    auto filtered_columns = [](const DenoiseSettings& settings, double* noise_before, double* noise_after) {
        Film film = flat_film(0.2f, 0.2f, 0.2f);
        for (int y = 0; y < 48; ++y)
            for (int x = 32; x < 64; ++x)
                for (int c = 0; c < 3; ++c) film.rgb[3 * (y * 64 + x) + c] = 0.3f;
        add_noise(film, 13, 0.8);
        *noise_before = mean_abs_error(film, 0, 24, 0.2f);
        denoise(film, 1.0, settings);
        *noise_after = mean_abs_error(film, 0, 24, 0.2f);
        std::vector<double> columns(64);
        for (int x = 0; x < 64; ++x) {
            for (int y = 0; y < 48; ++y) columns[x] += film.rgb[3 * (y * 64 + x)];
            columns[x] /= 48;
        }
        return columns;
    };
    double noise_before, noise_after;
    const std::vector<double> column = filtered_columns({}, &noise_before, &noise_after);
    EXPECT_LT(noise_after, 0.3 * noise_before);
    EXPECT_GT(column[33] - column[30], 0.06);
    for (int x = 0; x <= 28; ++x) EXPECT_NEAR(column[x], 0.2, 0.01) << x;
    for (int x = 35; x < 64; ++x) EXPECT_NEAR(column[x], 0.3, 0.01) << x;

    DenoiseSettings blind;
    blind.sigma_luminance = 1e9;
    const std::vector<double> blurred = filtered_columns(blind, &noise_before, &noise_after);
    EXPECT_LT(blurred[33] - blurred[30], 0.05) << "the test would not notice a blurred step";
}
