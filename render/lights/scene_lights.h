// The scene's emitters for next-event estimation: street-lamp globes (spheres, lamp_shape.h)
// and lit windows, chosen through a LightSampler (tree, power or uniform).
//
// Lit windows store nothing per window: a light is a strip of one wall, up to kFloorsPerStrip
// floors by kSlotsPerStrip slots, carrying the summed power of its lit windows; sampling it picks
// one lit window from the facade rules (window_lit, window_glow.h) in proportion to its power
// (choose_in_proportion: the strip keeps which cells are lit and its brightest window's power)
// and a point on the part of its pane the shading point sees through the opening.
// Strips are small (a few metres) so that the light BVH, not the choice inside a strip, tells
// the near windows from the far ones.
// Sun, moon and sky are not here: the integrator samples them beside these.
#pragma once

#include <algorithm>
#include <cstdint>
#include <functional>
#include <vector>

#include "common/scene.h"
#include "render/facade/facade.h"
#include "render/lights/light_sampler.h"
#include "render/materials/materials.h"
#include "render/scene/hit.h"

namespace citygen {

// Picks one of `count` candidates with probability weight(i) / (the sum of all weights), each
// weight at most `bound`, usually without working out every weight: a uniform candidate is kept
// with probability weight(i) / bound (rejection sampling), the retries' numbers taken from u
// itself (what is left of it after each step, rescaled to [0, 1)). After `rounds` refusals it
// chooses by summing all weights: a mixture of two choices in proportion to weight is one too.
// -1 when every weight is 0.
template <class Weight>
int choose_in_proportion(int count, double bound, int rounds, double u, const Weight& weight) {
    constexpr double kBelowOne = 0x1.fffffffffffffp-1;
    for (int round = 0; round < rounds && count > 0 && bound > 0; ++round) {
        const double x = u * count;
        const int i = std::min(static_cast<int>(x), count - 1);
        const double v = std::min(x - i, kBelowOne);
        const double keep = weight(i) / bound;
        if (v < keep) return i;
        u = std::min((v - keep) / (1 - keep), kBelowOne);
    }
    double total = 0;
    for (int i = 0; i < count; ++i) total += weight(i);
    if (!(total > 0)) return -1;
    const double target = u * total;
    double sum = 0;
    int last = -1;
    for (int i = 0; i < count; ++i) {
        const double w = weight(i);
        if (!(w > 0)) continue;
        last = i;
        sum += w;
        if (target < sum) break;
    }
    return last;  // the last with weight if rounding leaves target above the sum
}

struct LightOptions {
    bool lamps = true;                // lamps glow
    double lamp_lumens = 6000;        // --lamp-power: a typical LED street lamp
    double lamp_kelvin = 4000;        // --lamp-kelvin
    double lit_windows = 0.3;         // --lit-windows: share of windows lit (0: none)
    LightSamplerKind sampler = LightSamplerKind::Tree;
};

// A point on a lit window's pane: its radiance is the window's colour times its noise pattern.
struct WindowPoint {
    uint64_t key = 0;  // window_key
    bool shop = false;
    double s = 0, t = 0;  // across the pane, in [0, 1]
    Color radiance() const;
    double mean_luminance() const;  // of the whole pane (its noise pattern's mean)
};

struct LightSample {
    Vec3 position;     // on the emitter
    Vec3 direction;    // unit, from the shading point towards position
    double distance = 0;
    double pdf = 0;    // solid angle at the shading point, times the probability of the light
    // Radiance leaving the emitter towards the shading point. A window's is worked out only when
    // asked: most shadow rays are blocked, and the noise pattern is the dearest part of a sample.
    Color radiance() const { return window ? window_point.radiance() : lamp_radiance; }
    bool window = false;
    Color lamp_radiance{0, 0, 0};
    WindowPoint window_point;
};

class SceneLights {
public:
    SceneLights() = default;  // no emitters
    // `scene` must outlive this object (windows are re-derived from it when sampled).
    SceneLights(const Scene& scene, const FacadeOptions& facades, const LightOptions& options);

    bool empty() const { return light_count() == 0; }
    // Whether sampling reads the scene's buildings after construction (lit windows are derived
    // from them when sampled); otherwise the scene may go.
    bool reads_buildings() const { return options_.lit_windows > 0; }
    size_t light_count() const { return lamps_.size() + strips_.size(); }
    size_t lamp_count() const { return lamps_.size(); }
    size_t strip_count() const { return strips_.size(); }
    // Lamp i's globe, the sphere that glows.
    Vec3 lamp_center(size_t i) const { return {lamps_[i].center[0], lamps_[i].center[1], lamps_[i].center[2]}; }
    double lamp_radius(size_t i) const { return lamps_[i].radius; }
    uint64_t lit_window_count() const { return lit_windows_; }
    uint64_t window_count() const { return windows_; }
    // The light choice: light i < lamp_count() is lamp i, the rest window strips in order.
    bool choose_light(Vec3 p, Vec3 n, double u, uint32_t* light, double* pmf) const;
    double light_pmf(Vec3 p, Vec3 n, uint32_t light) const;
    size_t bytes() const;

    // Next-event estimation from point p with normal n (oriented to the side light may come from;
    // zero in a medium); u holds four uniform numbers. False when nothing was sampled.
    bool sample(Vec3 p, Vec3 n, const double u[4], LightSample* out) const;
    // Radiance an emitter sends back along the ray that hit it (front side), zero for anything else.
    Color emitted(const Hit& hit) const;
    // The pdf sample() from (p, n) has of producing the direction to `hit` (an emitter), as in LightSample.
    double pdf(Vec3 p, Vec3 n, const Hit& hit) const;

    // Whether the pane at `hit` belongs to a lit window (tests).
    bool lit_window_at(const Hit& hit) const;
    // A lit window's pane as one point sees it, for the film's gathering (small_emitters.h): the
    // part of it seen through its opening (visible_pane) widened by kSeenPaneMargin for
    // rounding, as world corners, and the building, wall and cell a Hit on it carries.
    struct SeenPane {
        uint32_t building, wall, cell;
        Vec3 corner[4];
    };
    // Calls visit(pane), in the strips' order, for every lit window whose pane's front `eye`
    // sees some of and that wanted(pane) keeps. The strips are walked on all threads (each wall
    // derives its layout: millions in a metropolis), so wanted is called from several at once.
    void for_each_lit_pane(Vec3 eye, const std::function<bool(const SeenPane&)>& wanted,
                           const std::function<void(const SeenPane&)>& visit) const;
    static constexpr double kSeenPaneMargin = 0.01;  // metres: stored panes are float triangles

    // A window strip's size: at most this many floors by slots of one wall.
    static constexpr int kFloorsPerStrip = 4, kSlotsPerStrip = 4;
    static_assert(kFloorsPerStrip * kSlotsPerStrip <= 16, "Strip::lit keeps one bit per cell");

private:
    struct Lamp {
        float center[3];
        float radius;
    };
    struct Strip {
        uint32_t building, wall;
        uint16_t first_floor, first_slot;
        uint8_t floor_count, slot_count;
        uint16_t lit;      // bit (floor - first_floor) x slot_count + slot - first_slot: the cell's window is lit
        float weight;      // sum of the lit windows' weights (window_weight)
        float max_weight;  // the largest of them, rounded up
    };
    struct WallGeometry {
        WallLayout layout;
        WallFrame frame;
        uint64_t building_key;
        uint32_t wall;
    };
    // The window strips of a run of buildings, gathered on their own thread and joined in order.
    struct StripBatch {
        std::vector<Strip> strips;
        std::vector<LightBounds> bounds;
        std::vector<uint32_t> many_ring_buildings;
        std::vector<BuildingWalls> many_ring_walls;
        uint64_t windows = 0, lit_windows = 0;
    };
    // The constructor's parts: each adds its emitters and their bounds (in sampler order).
    void gather_lamps(std::vector<LightBounds>& bounds);
    void gather_window_strips(std::vector<LightBounds>& bounds);
    void gather_window_strips(uint32_t begin, uint32_t end, StripBatch& batch) const;
    void add_window_strip(const WallGeometry& g, uint32_t b, uint32_t w, int first, int first_slot,
                          StripBatch& batch) const;
    bool wall_geometry(uint32_t building, uint32_t wall, WallGeometry* out) const;  // cached per thread
    bool derive_wall_geometry(const BuildingWalls& walls, uint32_t building, uint32_t wall, WallGeometry* out) const;
    double window_weight(const WallGeometry& g, int floor, int slot) const;  // 0: dark
    double lit_window_weight(const WallGeometry& g, int floor, int slot) const;  // of a window known lit
    // Light index of the strip holding a pane hit; -1 if none.
    int64_t strip_light(const Hit& hit) const;
    WindowPoint window_point(const WallGeometry& g, int floor, int slot, Vec3 position) const;
    bool sample_lamp(const Lamp& lamp, Vec3 p, double u1, double u2, LightSample* out) const;
    double lamp_pdf(const Lamp& lamp, Vec3 p) const;

    uint64_t id_ = 0;  // tells this instance's entries in the per-thread wall cache from others'
    const Scene* scene_ = nullptr;
    FacadeOptions facades_;
    LightOptions options_;
    Color lamp_radiance_{0, 0, 0};
    std::vector<Lamp> lamps_;             // light i < lamps_.size(): lamp i of the scene
    std::vector<Strip> strips_;           // light lamps_.size() + j: strip j, by (building, wall, floor, slot)
    // The walls of buildings of more than BuildingWalls::kInlineRings rings, by building index
    // (ascending): finding a wall again on each cache miss would cost O(rings) for these.
    std::vector<uint32_t> many_ring_buildings_;
    std::vector<BuildingWalls> many_ring_walls_;
    // Per building, the ground its walls stand on (building_base walks the whole outline over
    // the height field: worked out once, not at each wall-cache miss while rendering).
    std::vector<double> building_bases_;
    uint64_t lit_windows_ = 0, windows_ = 0;
    // With the tree, lamps and window strips have a light BVH each: in one tree over both, the
    // thousands of dim strips widened the clusters holding the lamps, and the lamp choice at the
    // street's first hits strayed far from proportional to the lamps' unshadowed light
    // (docs/bench/2026-11-night.md). Uniform and power choose among all lights at once, as their
    // names say.
    std::unique_ptr<LightSampler> sampler_;        // all lights; with the tree, the lamps (null: no lights)
    std::unique_ptr<LightSampler> strip_sampler_;  // with the tree, the window strips (null unless split_)
    // With the tree, the probability of choosing among the lamps. Not their share of the power:
    // a window's light leaves a recessed pane, mostly sideways and upwards into other facades,
    // and most window samples end in the shadow roulette, while a lamp lights the street below
    // it. Nor the two trees' root importance (the rule of a node above both roots): the lamps'
    // box lies metres above the road, the strips' box holds every shading point, so the windows
    // would get most samples. 0.9 was chosen on tests/bench/night_bench.sh's street and elevated
    // views (docs/bench/2026-11-night.md, third round).
    static constexpr double kLampShare = 0.9;
    bool split_ = false;
};

}  // namespace citygen
