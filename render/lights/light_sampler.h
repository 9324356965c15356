// Choosing one emitter for next-event estimation among thousands (--light-sampler):
//   tree    - a light BVH (pbrt-v4's BVHLightSampler, after Conty & Kulla 2018): descend from the
//             root, picking each child in proportion to its importance for the shading point
//             (power x orientation bound / distance^2 x surface-cosine bound);
//   power   - in proportion to each light's power, wherever the shading point is;
//   uniform - every light alike.
// pmf() gives the probability sample() has of picking a given light at the same point, so a
// path that hits an emitter can weight it by multiple importance sampling.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "light_bounds.h"

namespace citygen {

enum class LightSamplerKind { Tree, Power, Uniform };
LightSamplerKind parse_light_sampler(const std::string& text);  // throws citygen::Error
const char* to_string(LightSamplerKind kind);

class LightSampler {
public:
    LightSampler() = default;
    LightSampler(const std::vector<LightBounds>& lights, LightSamplerKind kind);

    size_t size() const { return light_count_; }
    LightSamplerKind kind() const { return kind_; }
    // Picks a light for point p with normal n (zero in a medium) from one uniform number.
    // False only when there are no lights (or none with power).
    bool sample(Vec3 p, Vec3 n, double u, uint32_t* light, double* pmf) const;
    double pmf(Vec3 p, Vec3 n, uint32_t light) const;
    size_t bytes() const;

private:
    struct Node {
        CompactLightBounds bounds;
        uint32_t index = 0;  // leaf: kLeaf | the light; interior: its first child (the second follows it)
        bool leaf() const { return index & kLeaf; }
        uint32_t light() const { return index & ~kLeaf; }
    };
    static constexpr uint32_t kLeaf = 0x80000000u;
    struct Item {
        LightBounds bounds;
        uint32_t light;
    };
    double first_child_probability(const LightQuery& q, uint32_t node) const;
    // Builds the subtree of items [begin, end) in node `self`; its bounds go to `bounds`.
    // Siblings are stored side by side, so each step down reads one place in memory.
    void build(std::vector<Item>& items, size_t begin, size_t end, uint64_t trail, int depth, uint32_t self,
               LightBounds* bounds);

    LightSamplerKind kind_ = LightSamplerKind::Tree;
    size_t light_count_ = 0;
    std::vector<Node> nodes_;          // tree, depth first
    std::vector<uint64_t> trails_;     // tree: per light, the child taken at each depth (bit d)
    std::vector<double> cdf_;          // power: running sum of powers
};

}  // namespace citygen
