// Deterministic randomness. Every random choice is a pure function of (seed, keys), so
// results never depend on iteration order or thread count.
#pragma once

#include <cstdint>

namespace citygen {

// SplitMix64 finaliser: a good 64-bit mixing function.
constexpr uint64_t mix64(uint64_t z) {
    z += 0x9e3779b97f4a7c15ull;
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
}

constexpr uint64_t hash_keys(uint64_t seed) { return mix64(seed); }
template <typename... Rest>
constexpr uint64_t hash_keys(uint64_t seed, uint64_t key, Rest... rest) {
    return hash_keys(mix64(seed ^ mix64(key)), static_cast<uint64_t>(rest)...);
}

// A uniform double in [0, 1) from a hash.
inline double hash_to_unit(uint64_t h) { return static_cast<double>(h >> 11) * 0x1.0p-53; }

// PCG32: a small, fast stream generator for per-pixel and per-object sequences.
class Rng {
public:
    explicit Rng(uint64_t stream_seed, uint64_t stream = 0)
        : state_(0), inc_((stream << 1u) | 1u) {
        next_u32();
        state_ += stream_seed;
        next_u32();
    }
    uint32_t next_u32() {
        uint64_t old = state_;
        state_ = old * 6364136223846793005ull + inc_;
        uint32_t xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
        uint32_t rot = static_cast<uint32_t>(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((-rot) & 31));
    }
    // Uniform in [0, 1), never 1.
    float next_float() { return static_cast<float>(next_u32() >> 8) * 0x1.0p-24f; }
    double next_double() { return hash_to_unit((static_cast<uint64_t>(next_u32()) << 32) | next_u32()); }

private:
    uint64_t state_, inc_;
};

}  // namespace citygen
