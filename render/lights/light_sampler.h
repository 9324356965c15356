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
#include <memory>
#include <string>
#include <vector>

#include "render/lights/light_bounds.h"

namespace citygen {

enum class LightSamplerKind { Tree, Power, Uniform };
LightSamplerKind parse_light_sampler(const std::string& text);  // throws citygen::Error
const char* to_string(LightSamplerKind kind);

// Chooses one light for a shading point; one class per strategy, made by make_light_sampler.
class LightSampler {
public:
    virtual ~LightSampler() = default;
    // Picks a light for point p with normal n (zero in a medium) from one uniform number.
    // False only when there are no lights (or none with power).
    virtual bool sample(Vec3 p, Vec3 n, double u, uint32_t* light, double* pmf) const = 0;
    // The probability sample() has of picking `light` at p.
    virtual double pmf(Vec3 p, Vec3 n, uint32_t light) const = 0;
    virtual size_t bytes() const = 0;
    size_t size() const { return light_count_; }

protected:
    explicit LightSampler(size_t light_count) : light_count_(light_count) {}
    const size_t light_count_;
};

// The sampler of the given strategy (--light-sampler) over these lights.
// Takes the bounds over: the tree build frees them as soon as it has its own copy.
std::unique_ptr<LightSampler> make_light_sampler(std::vector<LightBounds> lights, LightSamplerKind kind);

// Every light alike.
class UniformLightSampler final : public LightSampler {
public:
    explicit UniformLightSampler(const std::vector<LightBounds>& lights) : LightSampler(lights.size()) {}
    bool sample(Vec3 p, Vec3 n, double u, uint32_t* light, double* pmf) const override;
    double pmf(Vec3 p, Vec3 n, uint32_t light) const override;
    size_t bytes() const override { return 0; }
};

// In proportion to each light's power, wherever the shading point is.
class PowerLightSampler final : public LightSampler {
public:
    explicit PowerLightSampler(const std::vector<LightBounds>& lights);
    bool sample(Vec3 p, Vec3 n, double u, uint32_t* light, double* pmf) const override;
    double pmf(Vec3 p, Vec3 n, uint32_t light) const override;
    size_t bytes() const override { return cdf_.capacity() * sizeof(double); }

private:
    std::vector<double> cdf_;  // running sum of powers
};

// Down a light BVH, each child in proportion to its importance for the shading point.
class BVHLightSampler final : public LightSampler {
public:
    explicit BVHLightSampler(std::vector<LightBounds> lights);
    bool sample(Vec3 p, Vec3 n, double u, uint32_t* light, double* pmf) const override;
    double pmf(Vec3 p, Vec3 n, uint32_t light) const override;
    size_t bytes() const override;

private:
    // A node of the 4-wide tree: up to four children (the grandchildren of a node of the binary
    // tree the build makes, or its children where those are leaves).
    struct alignas(64) Node {  // three cache lines
        LightBounds4 bounds;
        uint32_t child[4];  // kLeaf | the light, or a node; lanes with no power are empty
    };
    static constexpr uint32_t kLeaf = 0x80000000u;
    static constexpr uint32_t kRoot = ~0u;
    static constexpr int kBuckets = 12;  // at most, per axis, for the split search
    struct Item {
        LightBounds bounds;
        uint32_t light;
    };
    struct BinaryNode {
        LightBounds bounds;
        uint32_t index = 0;  // leaf: kLeaf | the light; interior: its first child (the second follows it)
        uint32_t collapsed = 0;  // interior: how many 4-wide nodes collapse() makes of it
    };
    // Asks the cache for a node: on a large city the tree is far larger than the caches, and a
    // descent would otherwise wait on memory at every level.
    void prefetch(uint32_t node) const;
    // The probability of each of a node's lanes for q (empty lanes: 0).
    void lane_probabilities(const LightQuery& q, const Node& node, double p[4]) const;
    static int bucket_of(const Item& item, int axis, Vec3 cmin, double scale, int buckets);
    static int bucket_count(size_t lights);
    static void bucket_bounds(const std::vector<Item>& items, size_t begin, size_t end, Vec3 cmin, Vec3 cmax,
                              LightBounds buckets[3][kBuckets]);
    static void cheapest_split(const std::vector<Item>& items, size_t begin, size_t end, Vec3 cmin, Vec3 cmax,
                               int* best_axis, int* best_bucket);
    // Builds the binary subtree of items [begin, end) in tree[self] (siblings side by side), its
    // descendants from tree[next] on in depth-first order: a subtree of m lights has 2m - 1 nodes,
    // so both halves know their place and large ones are built side by side, the same tree.
    static void build(std::vector<Item>& items, size_t begin, size_t end, int depth, uint32_t self, uint32_t next,
                      std::vector<BinaryNode>& tree);
    // The binary nodes that become the lanes of the 4-wide node made from binary node b.
    static int lanes_of(const std::vector<BinaryNode>& tree, uint32_t b, uint32_t lanes[4]);
    // Makes node `self` of the 4-wide tree from binary node `b` and its descendants.
    void collapse(const std::vector<BinaryNode>& tree, uint32_t b, uint32_t self);

    std::vector<Node> nodes_;        // root first
    std::vector<uint32_t> parents_;  // per node, its parent x 4 + its lane there (root: kRoot)
    std::vector<uint32_t> leaf_of_;  // per light, the node holding it x 4 + its lane
};

}  // namespace citygen
