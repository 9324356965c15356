#include "render/integrator/pixel_jitter.h"

#include "common/rng.h"

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

// The first two dimensions of the Sobol sequence as 32-bit fractions are the van der Corput
// sequence (the index bit-reversed) and the XOR of direction numbers v_i = v_{i-1} ^ v_{i-1} >> 1
// over the index's set bits. This is the second with index and result both bit-reversed, a
// byte at a time from tables (the shuffled index has all 32 bits: 4 lookups, not 32 steps).
struct ReversedSobolSecond {
    uint32_t byte[4][256];
    ReversedSobolSecond() {
        // v[j]: for bit j of the reversed index (bit 31 - j of the index), that bit's direction
        // number, reversed.
        uint32_t v[32];
        uint32_t d = 0x80000000u;
        for (int i = 0; i < 32; ++i, d ^= d >> 1) v[31 - i] = reverse_bits(d);
        for (int k = 0; k < 4; ++k)
            for (uint32_t b = 0; b < 256; ++b) {
                uint32_t x = 0;
                for (int bit = 0; bit < 8; ++bit)
                    if (b >> bit & 1) x ^= v[8 * k + bit];
                byte[k][b] = x;
            }
    }
    uint32_t operator()(uint32_t reversed_index) const {
        return byte[0][reversed_index & 0xff] ^ byte[1][reversed_index >> 8 & 0xff] ^
               byte[2][reversed_index >> 16 & 0xff] ^ byte[3][reversed_index >> 24];
    }
};

double to_unit(uint32_t x) { return x * 0x1.0p-32; }

}  // namespace

PairSeeds pair_seeds(uint64_t pixel_key, uint32_t pair) {
    const uint64_t h = pair == 0 ? mix64(pixel_key) : mix64(hash_keys(pixel_key, pair));
    return {static_cast<uint32_t>(h), static_cast<uint32_t>(h >> 32), static_cast<uint32_t>(mix64(h) >> 32)};
}

Vec2 stratified_pair(const PairSeeds& seeds, uint32_t index) {
    static const ReversedSobolSecond reversed_second;
    // Shuffling the order keeps every aligned run of 2^k samples a (0,k,2)-net and decorrelates
    // pixels; the two scrambles randomise the point set itself. Each Owen scramble is
    // reverse(laine_karras(reverse(.))); the reversals that cancel are left out: the first
    // dimension is the reversed index, and the second is read from the reversed index directly.
    const uint32_t reversed_shuffled = laine_karras(reverse_bits(index), seeds.shuffle);
    const uint32_t shuffled = reverse_bits(reversed_shuffled);
    const uint32_t x = reverse_bits(laine_karras(shuffled, seeds.x));
    const uint32_t y = reverse_bits(laine_karras(reversed_second(reversed_shuffled), seeds.y));
    return {to_unit(x), to_unit(y)};
}

Vec2 stratified_pair(uint64_t pixel_key, uint32_t index, uint32_t pair) {
    return stratified_pair(pair_seeds(pixel_key, pair), index);
}

Vec2 pixel_jitter(uint64_t pixel_key, uint32_t index) { return stratified_pair(pixel_key, index, 0); }

}  // namespace citygen
