#include "pixel_jitter.h"

#include "rng.h"

namespace citygen {

namespace {

uint32_t reverse_bits(uint32_t x) {
    x = ((x >> 1) & 0x55555555u) | ((x & 0x55555555u) << 1);
    x = ((x >> 2) & 0x33333333u) | ((x & 0x33333333u) << 2);
    x = ((x >> 4) & 0x0f0f0f0fu) | ((x & 0x0f0f0f0fu) << 4);
    x = ((x >> 8) & 0x00ff00ffu) | ((x & 0x00ff00ffu) << 8);
    return (x >> 16) | (x << 16);
}

// A hash in which each bit depends only on the bits below it (Laine and Karras 2011): applied
// to reversed bits it is a nested uniform (Owen) scramble, each bit flipped by a hash of the
// bits above it.
uint32_t laine_karras(uint32_t x, uint32_t seed) {
    x += seed;
    x ^= x * 0x6c50b47cu;
    x ^= x * 0xb82f1e52u;
    x ^= x * 0xc7afe638u;
    x ^= x * 0x8d22f6e6u;
    return x;
}

uint32_t owen_scramble(uint32_t x, uint32_t seed) { return reverse_bits(laine_karras(reverse_bits(x), seed)); }

// The first two dimensions of the Sobol sequence as 32-bit fractions: the van der Corput
// sequence, and the second dimension's generator (direction numbers v_i = v_{i-1} ^ v_{i-1} >> 1).
uint32_t sobol_first(uint32_t index) { return reverse_bits(index); }
uint32_t sobol_second(uint32_t index) {
    uint32_t x = 0;
    for (uint32_t v = 0x80000000u; index; index >>= 1, v ^= v >> 1)
        if (index & 1) x ^= v;
    return x;
}

double to_unit(uint32_t x) { return x * 0x1.0p-32; }

}  // namespace

Vec2 pixel_jitter(uint64_t pixel_key, uint32_t index) { return stratified_pair(pixel_key, index, 0); }

Vec2 stratified_pair(uint64_t pixel_key, uint32_t index, uint32_t pair) {
    const uint64_t h = pair == 0 ? mix64(pixel_key) : mix64(hash_keys(pixel_key, pair));
    // Shuffling the order keeps every aligned run of 2^k samples a (0,k,2)-net and decorrelates
    // pixels; the two scrambles randomise the point set itself.
    const uint32_t shuffled = owen_scramble(index, static_cast<uint32_t>(h));
    const uint32_t x = owen_scramble(sobol_first(shuffled), static_cast<uint32_t>(h >> 32));
    const uint32_t y = owen_scramble(sobol_second(shuffled), static_cast<uint32_t>(mix64(h) >> 32));
    return {to_unit(x), to_unit(y)};
}

}  // namespace citygen
