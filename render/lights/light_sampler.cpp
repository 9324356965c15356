#include "render/lights/light_sampler.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <utility>

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "common/error.h"

namespace citygen {

namespace {

constexpr double kMostShare = 0.75;  // weight of the nearest-point share in a descent step
constexpr int kMaxSahDepth = 40;  // below this, plain median splits
constexpr size_t kParallelItems = 4096;  // nodes this large are built with both halves side by side
constexpr uint32_t kParallelNodes = 1024;  // 4-wide subtrees this large are made side by side

// The solid angle term of pbrt-v4's cost, a function of the two cone angles only. The split
// searches cost the same few cones over and over (a single direction, the whole sphere, the
// cones of a street's facades), so each thread remembers the values it worked out.
class OrientationMeasure {
public:
    double operator()(float cos_theta_o, float cos_theta_e) {
        uint32_t o, e;
        std::memcpy(&o, &cos_theta_o, 4);
        std::memcpy(&e, &cos_theta_e, 4);
        const uint64_t key = uint64_t(o) << 32 | e;
        Entry& entry = entries_[(key * 0x9E3779B97F4A7C15ull) >> (64 - kLogEntries)];
        if (entry.key == key) return entry.value;
        const double theta_o = std::acos(std::clamp(double(cos_theta_o), -1.0, 1.0));
        const double theta_e = std::acos(std::clamp(double(cos_theta_e), -1.0, 1.0));
        const double theta_w = std::min(theta_o + theta_e, kPi);
        const double sin_o = std::sin(theta_o);
        entry.key = key;
        entry.value = 2 * kPi * (1 - std::cos(theta_o)) +
                      kPi / 2 * (2 * theta_w * sin_o - std::cos(theta_o - 2 * theta_w) - 2 * theta_o * sin_o +
                                 std::cos(theta_o));
        return entry.value;
    }

private:
    static constexpr int kLogEntries = 12;
    struct Entry {
        uint64_t key = ~uint64_t{0};  // NaN cosines: no cone's
        double value = 0;
    };
    Entry entries_[1 << kLogEntries];
};

// pbrt-v4's cost of a cluster for the split search: power x solid angle of its orientation
// cone x surface area, stretched for thin boxes across the split axis.
double cluster_cost(const LightBounds& b, int axis, OrientationMeasure& orientation) {
    if (b.phi <= 0) return 0;
    const double m_omega = orientation(b.cos_theta_o, b.cos_theta_e);
    const Vec3 d = b.max() - b.min();
    const double longest = std::max({d.x, d.y, d.z});
    const double kr = d[axis] > 0 ? longest / d[axis] : 1;
    const double area = 2 * (d.x * d.y + d.y * d.z + d.z * d.x);
    return b.phi * m_omega * kr * std::max(area, 1e-6);
}

}  // namespace

LightSamplerKind parse_light_sampler(const std::string& text) {
    if (text == "tree") return LightSamplerKind::Tree;
    if (text == "power") return LightSamplerKind::Power;
    if (text == "uniform") return LightSamplerKind::Uniform;
    throw Error("--light-sampler: expected tree, power or uniform, got '" + text + "'");
}

const char* to_string(LightSamplerKind kind) {
    switch (kind) {
        case LightSamplerKind::Tree: return "tree";
        case LightSamplerKind::Power: return "power";
        case LightSamplerKind::Uniform: return "uniform";
    }
    return "?";
}

std::unique_ptr<LightSampler> make_light_sampler(std::vector<LightBounds> lights, LightSamplerKind kind) {
    if (lights.size() >= 0x80000000u) throw Error("too many lights for the light sampler");
    switch (kind) {
        case LightSamplerKind::Uniform: return std::make_unique<UniformLightSampler>(lights);
        case LightSamplerKind::Power: return std::make_unique<PowerLightSampler>(lights);
        case LightSamplerKind::Tree: break;
    }
    return std::make_unique<BVHLightSampler>(std::move(lights));
}

bool UniformLightSampler::sample(Vec3, Vec3, double u, uint32_t* light, double* pmf) const {
    if (light_count_ == 0) return false;
    const size_t i = std::min(static_cast<size_t>(u * light_count_), light_count_ - 1);
    *light = static_cast<uint32_t>(i);
    *pmf = 1.0 / light_count_;
    return true;
}

double UniformLightSampler::pmf(Vec3, Vec3, uint32_t light) const {
    return light < light_count_ ? 1.0 / light_count_ : 0;
}

PowerLightSampler::PowerLightSampler(const std::vector<LightBounds>& lights) : LightSampler(lights.size()) {
    cdf_.resize(lights.size());
    double sum = 0;
    for (size_t i = 0; i < lights.size(); ++i) cdf_[i] = sum += std::max(0.0f, lights[i].phi);
}

bool PowerLightSampler::sample(Vec3, Vec3, double u, uint32_t* light, double* pmf) const {
    if (light_count_ == 0) return false;
    const double total = cdf_.back();
    if (!(total > 0)) return false;
    const size_t i =
        std::min<size_t>(std::upper_bound(cdf_.begin(), cdf_.end(), u * total) - cdf_.begin(), light_count_ - 1);
    const double phi = cdf_[i] - (i ? cdf_[i - 1] : 0);
    if (!(phi > 0)) return false;
    *light = static_cast<uint32_t>(i);
    *pmf = phi / total;
    return true;
}

double PowerLightSampler::pmf(Vec3, Vec3, uint32_t light) const {
    if (light >= light_count_) return 0;
    const double total = cdf_.back();
    return total > 0 ? (cdf_[light] - (light ? cdf_[light - 1] : 0)) / total : 0;
}

BVHLightSampler::BVHLightSampler(std::vector<LightBounds> lights) : LightSampler(lights.size()) {
    if (lights.empty()) return;
    // Each copy is given back once the next step has what it needs (a city's millions of window
    // strips make these the largest arrays of the night's set-up).
    std::vector<Item> items(lights.size());
    for (size_t i = 0; i < lights.size(); ++i) items[i] = {lights[i], static_cast<uint32_t>(i)};
    lights = {};
    std::vector<BinaryNode> tree(2 * items.size() - 1);
    build(items, 0, items.size(), 0, 0, 1, tree);
    items = {};
    leaf_of_.assign(light_count_, 0);
    const size_t nodes = tree[0].index & kLeaf ? 1 : tree[0].collapsed;  // sized exactly: no regrowth, no spare
    if (nodes >= kLeaf / 4) throw Error("too many lights for the light sampler");
    nodes_.resize(nodes);
    parents_.resize(nodes);
    parents_[0] = kRoot;
    collapse(tree, 0, 0);
}

int BVHLightSampler::lanes_of(const std::vector<BinaryNode>& tree, uint32_t b, uint32_t lanes[4]) {
    // b's children, each replaced by its own two children where it has them (a lone light at the
    // root is a node with one lane).
    int count = 0;
    if (tree[b].index & kLeaf) {
        lanes[count++] = b;
        return count;
    }
    for (uint32_t c = tree[b].index; c < tree[b].index + 2; ++c) {
        if (tree[c].index & kLeaf) {
            lanes[count++] = c;
        } else {
            lanes[count++] = tree[c].index;
            lanes[count++] = tree[c].index + 1;
        }
    }
    return count;
}

void BVHLightSampler::collapse(const std::vector<BinaryNode>& tree, uint32_t b, uint32_t self) {
    // The 4-wide nodes in depth-first order, each subtree's from the node after its root on: the
    // lanes' subtrees know their places, and large ones are made side by side.
    uint32_t lanes[4], lane_node[4];
    const int count = lanes_of(tree, b, lanes);
    uint32_t next = self + 1;
    for (int lane = 0; lane < count; ++lane) {
        const BinaryNode& child = tree[lanes[lane]];
        nodes_[self].bounds.set(lane, child.bounds);
        if (child.index & kLeaf) {
            nodes_[self].child[lane] = child.index;
            leaf_of_[child.index & ~kLeaf] = self * 4 + lane;
        } else {
            lane_node[lane] = next;
            parents_[next] = self * 4 + lane;
            nodes_[self].child[lane] = next;
            next += child.collapsed;
        }
    }
    for (int lane = count; lane < 4; ++lane) nodes_[self].child[lane] = kLeaf;  // empty: power 0, never chosen
    auto collapse_lane = [&](int lane) {
        if (!(tree[lanes[lane]].index & kLeaf)) collapse(tree, lanes[lane], lane_node[lane]);
    };
    if (next - self >= kParallelNodes) {
        tbb::parallel_for(0, count, collapse_lane);
    } else {
        for (int lane = 0; lane < count; ++lane) collapse_lane(lane);
    }
}

// The bucket along `axis` of a light: `scale` is the bucket count over the centroids' extent.
int BVHLightSampler::bucket_of(const Item& item, int axis, Vec3 cmin, double scale, int buckets) {
    const int b = static_cast<int>((item.bounds.centroid()[axis] - cmin[axis]) * scale);
    return std::clamp(b, 0, buckets - 1);
}

// No more buckets than lights: a small node, most of the tree, costs as few candidates as it has lights.
int BVHLightSampler::bucket_count(size_t lights) { return static_cast<int>(std::min<size_t>(kBuckets, lights)); }

// The bounds of the lights in each bucket along each axis (axes with no extent left empty), for
// the split's cost only (the tree's own nodes are joined exactly, in build()): boxes, power and
// emission angle as join() makes them, but each normal cone centred on the bucket's mean normal
// and as wide as its farthest light needs. Joining the cones one light at a time (pbrt-v4's
// Union) costs inverse cosines each time the cone grows, and a city's facades face every way, so
// it grows all the time. Two passes over the lights, each for the three axes at once: the lights
// of the upper nodes are far larger than the caches.
void BVHLightSampler::bucket_bounds(const std::vector<Item>& items, size_t begin, size_t end, Vec3 cmin, Vec3 cmax,
                                    LightBounds buckets[3][kBuckets]) {
    const double extent[3] = {cmax.x - cmin.x, cmax.y - cmin.y, cmax.z - cmin.z};
    const int count = bucket_count(end - begin);
    int axes[3], axis_count = 0;
    double scale[3];
    for (int axis = 0; axis < 3; ++axis) {
        scale[axis] = count / extent[axis];
        if (extent[axis] > 0) axes[axis_count++] = axis;
    }
    Vec3 normal_sum[3][kBuckets] = {};
    bool everywhere[3][kBuckets] = {};
    for (size_t i = begin; i < end; ++i) {
        const LightBounds& light = items[i].bounds;
        if (!(light.phi > 0)) continue;  // as join(): no power, no bounds
        for (int a = 0; a < axis_count; ++a) {
            const int axis = axes[a];
            const int b = bucket_of(items[i], axis, cmin, scale[axis], count);
            LightBounds& bucket = buckets[axis][b];
            for (int k = 0; k < 3; ++k) {
                bucket.lo[k] = std::min(bucket.lo[k], light.lo[k]);
                bucket.hi[k] = std::max(bucket.hi[k], light.hi[k]);
            }
            bucket.cos_theta_e = bucket.phi > 0 ? std::min(bucket.cos_theta_e, light.cos_theta_e) : light.cos_theta_e;
            bucket.phi += light.phi;
            bucket.two_sided = bucket.two_sided || light.two_sided;
            everywhere[axis][b] = everywhere[axis][b] || light.cos_theta_o <= -1;
            normal_sum[axis][b] = normal_sum[axis][b] + light.axis();
        }
    }
    float min_cos[3][kBuckets];
    bool any_cone = false;
    for (int a = 0; a < axis_count; ++a)
        for (int b = 0, axis = axes[a]; b < count; ++b) {
            min_cos[axis][b] = 1;
            const double length = std::sqrt(dot(normal_sum[axis][b], normal_sum[axis][b]));
            everywhere[axis][b] = everywhere[axis][b] || !(length > 1e-9);  // normals that cancel out
            if (buckets[axis][b].phi > 0 && !everywhere[axis][b]) {
                buckets[axis][b].set_axis(normal_sum[axis][b] * (1 / length));
                any_cone = true;
            }
        }
    // The widest angle from the axis of each light's cone: the angle to its axis plus its own
    // half angle, by the sum formulas (past pi: every direction).
    for (size_t i = begin; any_cone && i < end; ++i) {
        const LightBounds& light = items[i].bounds;
        if (!(light.phi > 0)) continue;
        const double cos_t = light.cos_theta_o, sin_t = std::sqrt(std::max(0.0, 1 - cos_t * cos_t));
        for (int a = 0; a < axis_count; ++a) {
            const int axis = axes[a];
            const int b = bucket_of(items[i], axis, cmin, scale[axis], count);
            if (everywhere[axis][b]) continue;
            const float* w = buckets[axis][b].w;
            const double cos_a = std::clamp(
                double(light.w[0]) * w[0] + double(light.w[1]) * w[1] + double(light.w[2]) * w[2], -1.0, 1.0);
            double c = cos_a;
            if (cos_t < 1) {
                const double sin_a = std::sqrt(std::max(0.0, 1 - cos_a * cos_a));
                c = sin_a * cos_t + cos_a * sin_t < 0 ? -1 : cos_a * cos_t - sin_a * sin_t;
            }
            min_cos[axis][b] = std::min(min_cos[axis][b], static_cast<float>(c));
        }
    }
    for (int a = 0; a < axis_count; ++a)
        for (int b = 0, axis = axes[a]; b < count; ++b) {
            LightBounds& bucket = buckets[axis][b];
            if (!(bucket.phi > 0)) continue;
            if (everywhere[axis][b] || min_cos[axis][b] <= -1) {
                bucket.set_axis_up();
                bucket.cos_theta_o = -1;
            } else {
                bucket.cos_theta_o = min_cos[axis][b];
            }
        }
}

// The bucket boundary of the cheapest split of items [begin, end) over the three axes (axis -1:
// none); the first of equal costs wins, in axis order.
void BVHLightSampler::cheapest_split(const std::vector<Item>& items, size_t begin, size_t end, Vec3 cmin, Vec3 cmax,
                                     int* best_axis, int* best_bucket) {
    LightBounds buckets[3][kBuckets];
    bucket_bounds(items, begin, end, cmin, cmax, buckets);
    const int buckets_per_axis = bucket_count(end - begin);
    thread_local OrientationMeasure orientation;
    double best_cost = 1e300;
    for (int axis = 0; axis < 3; ++axis) {
        // Costs of the splits from a sweep each way over the buckets that hold light (a split
        // next to an empty bucket divides the lights as the one before it: small nodes, most of
        // the tree, have few such buckets). below[j] holds the lights of filled[0..j], above[j]
        // those of filled[j+1..].
        const LightBounds* bucket = buckets[axis];
        int filled[kBuckets];
        int count = 0;
        for (int b = 0; b < buckets_per_axis; ++b)
            if (bucket[b].phi > 0) filled[count++] = b;
        if (count == 0) continue;
        LightBounds below[kBuckets], above[kBuckets];
        below[0] = bucket[filled[0]];
        for (int j = 1; j < count; ++j) below[j] = union_of(below[j - 1], bucket[filled[j]]);
        above[count - 1] = LightBounds{};
        if (count > 1) above[count - 2] = bucket[filled[count - 1]];
        for (int j = count - 3; j >= 0; --j) above[j] = union_of(above[j + 1], bucket[filled[j + 1]]);
        auto try_split = [&](int split, const LightBounds& low, const LightBounds& high) {
            const double cost = cluster_cost(low, axis, orientation) + cluster_cost(high, axis, orientation);
            if (cost < best_cost) {
                best_cost = cost;
                *best_axis = axis;
                *best_bucket = split;
            }
        };
        if (filled[0] > 0)  // nothing below: all of them above, joined in the same order
            try_split(0, LightBounds{}, count > 1 ? union_of(above[0], bucket[filled[0]]) : bucket[filled[0]]);
        for (int j = 0; j < count; ++j)
            if (filled[j] < buckets_per_axis - 1) try_split(filled[j], below[j], above[j]);
    }
}

void BVHLightSampler::build(std::vector<Item>& items, size_t begin, size_t end, int depth, uint32_t self,
                            uint32_t next, std::vector<BinaryNode>& tree) {
    if (end - begin == 1) {
        tree[self].bounds = items[begin].bounds;
        tree[self].index = kLeaf | items[begin].light;
        return;
    }
    Vec3 cmin{1e300, 1e300, 1e300}, cmax{-1e300, -1e300, -1e300};
    for (size_t i = begin; i < end; ++i) {
        const Vec3 c = items[i].bounds.centroid();
        cmin = {std::min(cmin.x, c.x), std::min(cmin.y, c.y), std::min(cmin.z, c.z)};
        cmax = {std::max(cmax.x, c.x), std::max(cmax.y, c.y), std::max(cmax.z, c.z)};
    }
    // Split: the cheapest bucket boundary over the three axes (SAH-like, pbrt-v4's cost), or the
    // median along the widest axis when the centroids coincide or the tree grows deep.
    const bool large = end - begin >= kParallelItems;
    int best_axis = -1, best_bucket = -1;
    // Two lights split one way only.
    if (depth < kMaxSahDepth && end - begin > 2) cheapest_split(items, begin, end, cmin, cmax, &best_axis, &best_bucket);
    size_t mid = begin;
    if (best_axis >= 0) {
        const double extent = cmax[best_axis] - cmin[best_axis];
        const int buckets = bucket_count(end - begin);
        const double scale = buckets / extent;
        auto below = [&](const Item& item) { return bucket_of(item, best_axis, cmin, scale, buckets) <= best_bucket; };
        mid = std::partition(items.begin() + begin, items.begin() + end, below) - items.begin();
    }
    if (mid == begin || mid == end) {  // no useful split: halve along the widest spread
        const Vec3 spread = cmax - cmin;
        const int axis = spread.x >= spread.y && spread.x >= spread.z ? 0 : (spread.y >= spread.z ? 1 : 2);
        mid = (begin + end) / 2;
        std::nth_element(items.begin() + begin, items.begin() + mid, items.begin() + end,
                         [axis](const Item& a, const Item& b) {
                             const double ca = a.bounds.centroid()[axis], cb = b.bounds.centroid()[axis];
                             return ca < cb || (ca == cb && a.light < b.light);
                         });
    }
    const uint32_t first = next;
    const uint32_t after_left = first + 2 * static_cast<uint32_t>(mid - begin);  // the left half's 2m - 2 descendants
    auto left = [&] { build(items, begin, mid, depth + 1, first, first + 2, tree); };
    auto right = [&] { build(items, mid, end, depth + 1, first + 1, after_left, tree); };
    if (large) {
        tbb::parallel_invoke(left, right);
    } else {
        left();
        right();
    }
    tree[self].bounds = union_of(tree[first].bounds, tree[first + 1].bounds);
    tree[self].index = first;
    uint32_t lanes[4];
    tree[self].collapsed = 1;
    for (int lane = 0, count = lanes_of(tree, self, lanes); lane < count; ++lane)
        tree[self].collapsed += tree[lanes[lane]].collapsed;  // a leaf's is 0
}

void BVHLightSampler::prefetch(uint32_t node) const {
    const char* bytes = reinterpret_cast<const char*>(&nodes_[node]);
    for (size_t offset = 0; offset < sizeof(Node); offset += 64) __builtin_prefetch(bytes + offset);
}

bool BVHLightSampler::sample(Vec3 p, Vec3 n, double u, uint32_t* light, double* pmf) const {
    if (light_count_ == 0) return false;
    const LightQuery q(p, n);
    uint32_t node = 0;
    double probability = 1;
    for (;;) {
        // Every child is fetched while this node's lanes are weighed: one of them is next.
        for (uint32_t child : nodes_[node].child)
            if (!(child & kLeaf)) prefetch(child);
        double lane_p[4];
        lane_probabilities(q, nodes_[node], lane_p);
        // The lane u falls in (the last with a chance if rounding leaves u above their sum),
        // and u rescaled to it for the next step.
        int lane = -1;
        for (int i = 0; i < 4; ++i) {
            if (!(lane_p[i] > 0)) continue;
            lane = i;
            if (u < lane_p[i]) break;
            u -= lane_p[i];
        }
        if (lane < 0) return false;
        u = std::min(u / lane_p[lane], 0x1.fffffffffffffp-1);
        probability *= lane_p[lane];
        const uint32_t child = nodes_[node].child[lane];
        if (child & kLeaf) {
            *light = child & ~kLeaf;
            *pmf = probability;
            return true;
        }
        node = child;
    }
}

double BVHLightSampler::pmf(Vec3 p, Vec3 n, uint32_t light) const {
    if (light >= light_count_) return 0;
    // The lanes from the light up to the root, then their probabilities multiplied from the
    // root down, in the order sample() multiplies them (the same double, bit for bit).
    uint32_t path[64];
    int depth = 0;
    for (uint32_t at = leaf_of_[light]; at != kRoot && depth < 64; at = parents_[at / 4]) path[depth++] = at;
    for (int i = 0; i < depth; ++i) prefetch(path[i] / 4);
    const LightQuery q(p, n);
    double probability = 1;
    while (depth > 0) {
        const uint32_t at = path[--depth];
        double lane_p[4];
        lane_probabilities(q, nodes_[at / 4], lane_p);
        probability *= lane_p[at % 4];
    }
    return probability;
}

// The chance of each lane: a blend of its share of the lanes' `most` bounds and of their
// `least` bounds (LightBounds4::importance; Cycles' light tree takes their mean): the
// nearest-point bound alone would favour any big cluster around p, the farthest-point bound
// alone any small one. Weighting the nearest-point share 3:1 gave the lowest error of the blends
// tried on the night street of tests/bench/night_bench.sh (docs/bench/2026-11-night.md).
// Where no lane can light p (the bounds are loose enough that a cluster may pass the test
// its children all fail), in proportion to power. So every descent ends at a light and the
// probabilities of all lights sum to one; a light that cannot reach p then contributes nothing.
void BVHLightSampler::lane_probabilities(const LightQuery& q, const Node& node, double p[4]) const {
    float most[4], least[4];
    node.bounds.importance(q, most, least);
    double sum_most = 0, sum_least = 0, sum_phi = 0;
    for (int i = 0; i < 4; ++i) {
        sum_most += most[i];
        sum_least += least[i];
        sum_phi += node.bounds.phi[i];
    }
    if (!(sum_most > 0)) {
        for (int i = 0; i < 4; ++i) p[i] = node.bounds.phi[i] / sum_phi;
        return;
    }
    // kMostShare x most / sum_most + (1 - kMostShare) x least / sum_least, two divisions a node.
    const double by_most = sum_least > 0 ? kMostShare / sum_most : 1 / sum_most;
    const double by_least = sum_least > 0 ? (1 - kMostShare) / sum_least : 0;
    for (int i = 0; i < 4; ++i) p[i] = most[i] * by_most + least[i] * by_least;
}

size_t BVHLightSampler::bytes() const {
    return nodes_.capacity() * sizeof(Node) + parents_.capacity() * sizeof(uint32_t) + leaf_of_.capacity() * sizeof(uint32_t);
}

}  // namespace citygen
