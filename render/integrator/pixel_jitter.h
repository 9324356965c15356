// Where in its pixel each camera sample goes: a 2D Sobol sequence (0,2)-sequence, Owen-scrambled
// and index-shuffled per pixel by hashing (Burley 2020, "Practical Hash-based Owen Scrambling").
// Any 2^k consecutive samples from the start cover the pixel evenly (one in each of the 2^k
// equal strips across or down, and each grid of 2^k cells), so the edges of bright emitters
// seen directly (lamp globes, lit windows) average out much faster than with independent jitter;
// each sample on its own is still uniform over the pixel, so the estimate stays unbiased.
// A pure function of (pixel key, sample index): the same whatever the thread, tile or pass.
#pragma once

#include <cstdint>

#include "common/geometry.h"

namespace citygen {

// Position of sample `index` of the pixel whose samples are keyed by `pixel_key`, in [0, 1)^2.
Vec2 pixel_jitter(uint64_t pixel_key, uint32_t index);

// Pair `pair` of a pixel's padded sequence: for each pair its own shuffle and scramble of the
// same 2D Sobol points (pair 0 is pixel_jitter), so every pair is stratified over the pixel's
// samples on its own and the pairs are independent of each other.
Vec2 stratified_pair(uint64_t pixel_key, uint32_t index, uint32_t pair);

// The same with the pair's seeds worked out once for all of a pixel's samples.
struct PairSeeds {
    uint32_t shuffle, x, y;
};
PairSeeds pair_seeds(uint64_t pixel_key, uint32_t pair);
Vec2 stratified_pair(const PairSeeds& seeds, uint32_t index);

}  // namespace citygen
