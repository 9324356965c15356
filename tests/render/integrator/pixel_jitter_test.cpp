// Where camera samples fall in their pixel (render/integrator/pixel_jitter.h): stratified, yet each sample
// uniform over the pixel.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "common/rng.h"
#include "render/integrator/pixel_jitter.h"

using namespace citygen;

TEST(PixelJitter, EveryPowerOfTwoPrefixCoversThePixelEvenly) {
    // 16 samples: one in each of the 16 columns, 16 rows and each cell of the 4x4, 2x8 and 8x2
    // grids (a (0,4,2)-net); likewise 64 samples in 8x8 cells. So are the other stratified
    // pairs (the first surface's numbers), pair 0 being the jitter itself.
    for (uint64_t key = 0; key < 1000; ++key) {
        const uint32_t pair = key % 5;
        for (int log2n : {4, 6}) {
            const int n = 1 << log2n;
            for (int columns_log2 = 0; columns_log2 <= log2n; ++columns_log2) {
                const int columns = 1 << columns_log2, rows = n / columns;
                std::vector<int> hits(n, 0);
                for (int i = 0; i < n; ++i) {
                    const Vec2 j = stratified_pair(key, static_cast<uint32_t>(i), pair);
                    if (pair == 0) {
                        ASSERT_EQ(j, pixel_jitter(key, static_cast<uint32_t>(i)));
                    }
                    ASSERT_GE(j.x, 0);
                    ASSERT_LT(j.x, 1);
                    ASSERT_GE(j.y, 0);
                    ASSERT_LT(j.y, 1);
                    ++hits[static_cast<int>(j.y * rows) * columns + static_cast<int>(j.x * columns)];
                }
                for (int c = 0; c < n; ++c)
                    ASSERT_EQ(hits[c], 1) << "key " << key << ", pair " << pair << ", " << n << " samples, " << columns << " columns, cell " << c;
            }
        }
    }
}

TEST(PixelJitter, EachSampleIsUniformOverThePixelAndPixelsDiffer) {
    // Sample 0 and sample 5 over many pixels: the counts in an 8x8 grid are what uniform
    // points give (chi-square with 63 degrees of freedom, far below its 99.9% point of 104).
    // Likewise for the first surface's pairs (1-4).
    for (uint32_t pair = 0; pair < 5; ++pair) {
        for (uint32_t index : {0u, 5u}) {
            constexpr int kCells = 64, kPixels = 64000;
            std::vector<int> counts(kCells, 0);
            for (uint64_t key = 0; key < kPixels; ++key) {
                const Vec2 j = stratified_pair(mix64(key), index, pair);
                ++counts[static_cast<int>(j.y * 8) * 8 + static_cast<int>(j.x * 8)];
            }
            const double expected = double(kPixels) / kCells;
            double chi2 = 0;
            for (int c : counts) chi2 += (c - expected) * (c - expected) / expected;
            EXPECT_LT(chi2, 104) << "pair " << pair << ", sample " << index;
        }
    }
    const Vec2 a = pixel_jitter(1, 0), b = pixel_jitter(2, 0);
    EXPECT_TRUE(a.x != b.x || a.y != b.y);
}

TEST(PixelJitter, StratifiedPairsAreIndependentOfEachOther) {
    // The same sample's numbers from two pairs, over many pixels and samples: uniform over the
    // unit square (chi-square with 63 degrees of freedom below its 99.9% point of 104). Pairs
    // sharing a shuffle or scramble would put them on a line or a lattice.
    for (uint32_t other : {2u, 3u, 4u}) {
        constexpr int kCells = 64;
        std::vector<int> counts(kCells, 0);
        int n = 0;
        for (uint64_t key = 0; key < 4000; ++key)
            for (uint32_t i = 0; i < 16; ++i, ++n) {
                const double a = stratified_pair(mix64(key), i, 1).x, b = stratified_pair(mix64(key), i, other).x;
                ++counts[static_cast<int>(a * 8) * 8 + static_cast<int>(b * 8)];
            }
        const double expected = double(n) / kCells;
        double chi2 = 0;
        for (int c : counts) chi2 += (c - expected) * (c - expected) / expected;
        EXPECT_LT(chi2, 104) << "pairs 1 and " << other;
    }
}
