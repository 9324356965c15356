#include "render/lights/scene_lights.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <optional>
#include <utility>
#include <tuple>

#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "render/geometry/ground.h"
#include "render/geometry/lamp_shape.h"
#include "render/lights/photometry.h"
#include "render/lights/window_glow.h"
#include "render/materials/bsdf.h"

namespace citygen {

namespace {

bool is_pane_material(uint16_t m) { return m == kGlass || m == kShopWindow; }

// Rejection rounds before a strip's window is chosen by summing: a round keeps its candidate
// with probability (its weight / the strip's brightest), about one in two; rarely all 8 refuse.
constexpr int kRejectionRounds = 8;

// 1 - cos of the half-angle a sphere of radius r subtends from distance d > r (stable when far).
double one_minus_cos_sphere(double r, double d) {
    const double sin2 = (r * r) / (d * d);
    return sin2 / (1 + std::sqrt(std::max(0.0, 1 - sin2)));
}

}  // namespace

SceneLights::SceneLights(const Scene& scene, const FacadeOptions& facades, const LightOptions& options)
    : scene_(&scene), facades_(facades), options_(options) {
    static std::atomic<uint64_t> instances{0};
    id_ = ++instances;  // never 0: an empty cache slot belongs to no instance
    std::vector<LightBounds> bounds;
    if (options.lamps && options.lamp_lumens > 0) gather_lamps(bounds);
    building_bases_.reserve(scene.buildings.size());
    for (const Building& b : scene.buildings) building_bases_.push_back(building_base(scene, b));
    if (options.lit_windows > 0) gather_window_strips(bounds);
    lamps_.shrink_to_fit();
    strips_.shrink_to_fit();
    split_ = options.sampler == LightSamplerKind::Tree && !lamps_.empty() && !strips_.empty();
    if (!split_) {
        sampler_ = make_light_sampler(std::move(bounds), options.sampler);
        return;
    }
    // The lamps' few bounds copied out, the strips' left in place (no second copy of the many).
    std::vector<LightBounds> lamp_bounds(bounds.begin(), bounds.begin() + lamps_.size());
    bounds.erase(bounds.begin(), bounds.begin() + lamps_.size());
    tbb::parallel_invoke([&] { strip_sampler_ = make_light_sampler(std::move(bounds), options.sampler); },
                         [&] { sampler_ = make_light_sampler(std::move(lamp_bounds), options.sampler); });
}

void SceneLights::gather_lamps(std::vector<LightBounds>& bounds) {
    const StandingSurface surface(*scene_);
    for (const citygen::Lamp& lamp : scene_->lamps) {
        const LampShape s = lamp_shape(lamp, lamp_ground(surface, lamp));
        const Vec3 c = s.globe_center;
        const double r = s.globe_radius;
        lamps_.push_back({{float(c.x), float(c.y), float(c.z)}, float(r)});
        LightBounds b;
        b.set_box(c - Vec3{r, r, r}, c + Vec3{r, r, r});
        b.cos_theta_o = -1;  // a sphere's normals point everywhere
        b.cos_theta_e = 0;
        // Luminous flux of a Lambertian sphere: pi x luminance x area.
        b.phi = static_cast<float>(options_.lamp_lumens);
        bounds.push_back(b);
    }
    // Lambertian sphere of area 4 pi r^2 sending lamp_lumens: L = flux / (pi * area).
    const double r = lamp_shape(citygen::Lamp{}, 0).globe_radius;
    const double nits = options_.lamp_lumens / (kPi * 4 * kPi * r * r);
    lamp_radiance_ = blackbody_color(options_.lamp_kelvin) * (nits / kNitsPerRadianceUnit);
}

void SceneLights::gather_window_strips(std::vector<LightBounds>& bounds) {
    constexpr uint32_t kBuildingsPerBatch = 512;
    const uint32_t n = static_cast<uint32_t>(scene_->buildings.size());
    std::vector<StripBatch> batches((n + kBuildingsPerBatch - 1) / kBuildingsPerBatch);
    tbb::parallel_for(size_t{0}, batches.size(), [&](size_t i) {
        const uint32_t begin = static_cast<uint32_t>(i) * kBuildingsPerBatch;
        gather_window_strips(begin, std::min(n, begin + kBuildingsPerBatch), batches[i]);
    });
    size_t strips = 0;
    for (const StripBatch& batch : batches) strips += batch.strips.size();
    strips_.reserve(strips);
    bounds.reserve(bounds.size() + strips);
    for (StripBatch& batch : batches) {
        strips_.insert(strips_.end(), batch.strips.begin(), batch.strips.end());
        bounds.insert(bounds.end(), batch.bounds.begin(), batch.bounds.end());
        many_ring_buildings_.insert(many_ring_buildings_.end(), batch.many_ring_buildings.begin(),
                                    batch.many_ring_buildings.end());
        for (BuildingWalls& walls : batch.many_ring_walls) many_ring_walls_.push_back(std::move(walls));
        windows_ += batch.windows;
        lit_windows_ += batch.lit_windows;
        batch = StripBatch{};
    }
}

void SceneLights::gather_window_strips(uint32_t begin, uint32_t end, StripBatch& batch) const {
    for (uint32_t b = begin; b < end; ++b) {
        const Building& building = scene_->buildings[b];
        if (!has_volume(building)) continue;
        const BuildingWalls walls(building);
        if (building.holes.size() + 1 > BuildingWalls::kInlineRings) {
            batch.many_ring_buildings.push_back(b);
            batch.many_ring_walls.push_back(walls);
        }
        for (uint32_t w = 0, n = static_cast<uint32_t>(walls.count()); w < n; ++w) {
            WallGeometry g;
            if (!derive_wall_geometry(walls, b, w, &g) || g.layout.plain()) continue;
            const WallLayout& L = g.layout;
            for (int first = 0; first < L.floors; first += kFloorsPerStrip)
                for (int first_slot = 0; first_slot < L.slots; first_slot += kSlotsPerStrip)
                    add_window_strip(g, b, w, first, first_slot, batch);
        }
    }
}

// The strip of windows from (first floor, first slot) on wall w of building b: kept with its
// bounds if any of its windows is lit.
void SceneLights::add_window_strip(const WallGeometry& g, uint32_t b, uint32_t w, int first, int first_slot,
                                   StripBatch& batch) const {
    const WallLayout& L = g.layout;
    const int count = std::min(kFloorsPerStrip, L.floors - first);
    const int slot_count = std::min(kSlotsPerStrip, L.slots - first_slot);
    double weight = 0, max_weight = 0;
    uint16_t lit = 0;
    for (int floor = first; floor < first + count; ++floor) {
        for (int slot = first_slot; slot < first_slot + slot_count; ++slot) {
            ++batch.windows;
            const double wgt = window_weight(g, floor, slot);
            if (!(wgt > 0)) continue;
            ++batch.lit_windows;
            lit |= uint16_t(1u << ((floor - first) * slot_count + slot - first_slot));
            weight += wgt;
            max_weight = std::max(max_weight, wgt);
        }
    }
    if (!(weight > 0)) return;
    float max_rounded = static_cast<float>(max_weight);  // a bound for rejection: never below
    if (max_rounded < max_weight) max_rounded = std::nextafter(max_rounded, 1e30f);
    batch.strips.push_back({b, w, static_cast<uint16_t>(first), static_cast<uint16_t>(first_slot),
                       static_cast<uint8_t>(count), static_cast<uint8_t>(slot_count), lit, float(weight), max_rounded});
    // Bounds: the strip's cells of the wall at the pane depth, facing out of the building.
    const double v0 = L.grid_v0 + first * L.floor_height, v1 = v0 + count * L.floor_height;
    const double u0 = L.grid_u0 + first_slot * L.slot_width, u1 = u0 + slot_count * L.slot_width;
    LightBounds lb;
    lb.set_box(g.frame.to_world(u0, v0, L.recess), g.frame.to_world(u1, v1, L.recess));
    lb.set_axis(-g.frame.w_axis);
    lb.cos_theta_o = 1;
    lb.cos_theta_e = 0;
    lb.phi = static_cast<float>(kPi * weight * kNitsPerRadianceUnit);  // lumens, as the lamps
    batch.bounds.push_back(lb);
}

bool SceneLights::choose_light(Vec3 p, Vec3 n, double u, uint32_t* light, double* pmf) const {
    if (!split_) return sampler_ && sampler_->sample(p, n, u, light, pmf);
    // One uniform number for both steps, rescaled after the first (as the tree's descent does).
    if (u < kLampShare) {
        if (!sampler_->sample(p, n, std::min(u / kLampShare, 0x1.fffffffffffffp-1), light, pmf)) return false;
        *pmf *= kLampShare;
        return true;
    }
    if (!strip_sampler_->sample(p, n, std::min((u - kLampShare) / (1 - kLampShare), 0x1.fffffffffffffp-1), light, pmf))
        return false;
    *pmf *= 1 - kLampShare;
    *light += static_cast<uint32_t>(lamps_.size());
    return true;
}

double SceneLights::light_pmf(Vec3 p, Vec3 n, uint32_t light) const {
    if (!split_) return sampler_ ? sampler_->pmf(p, n, light) : 0;
    if (light < lamps_.size()) return kLampShare * sampler_->pmf(p, n, light);
    return (1 - kLampShare) * strip_sampler_->pmf(p, n, light - static_cast<uint32_t>(lamps_.size()));
}

size_t SceneLights::bytes() const {
    return lamps_.capacity() * sizeof(Lamp) + strips_.capacity() * sizeof(Strip) + (sampler_ ? sampler_->bytes() : 0) +
           (strip_sampler_ ? strip_sampler_->bytes() : 0);
}

bool SceneLights::wall_geometry(uint32_t building, uint32_t wall, WallGeometry* out) const {
    // Deriving a wall's layout and frame from the rules is not cheap beside a shading step, and
    // the walls a pixel's paths sample or hit repeat: each thread keeps the last few (values only,
    // so the image cannot depend on the cache or the thread count).
    struct Cached {
        uint64_t owner = 0;
        uint32_t building = 0, wall = 0;
        bool ok = false;
        WallGeometry geometry;
    };
    thread_local Cached cache[256];
    Cached& slot = cache[(building * 31u + wall) & 255u];
    if (slot.owner == id_ && slot.building == building && slot.wall == wall) {
        *out = slot.geometry;
        return slot.ok;
    }
    slot.owner = id_;
    slot.building = building;
    slot.wall = wall;
    // The rings' orientation is found again on each miss (a few dozen flops beside deriving the
    // layout) rather than kept per building (memory for every building: docs/bench/2026-11-night.md).
    slot.ok = false;
    if (options_.lit_windows > 0 && building < scene_->buildings.size()) {
        const auto kept = std::lower_bound(many_ring_buildings_.begin(), many_ring_buildings_.end(), building);
        if (kept != many_ring_buildings_.end() && *kept == building)
            slot.ok = derive_wall_geometry(many_ring_walls_[kept - many_ring_buildings_.begin()], building, wall,
                                           &slot.geometry);
        else
            slot.ok = derive_wall_geometry(BuildingWalls(scene_->buildings[building]), building, wall, &slot.geometry);
    }
    *out = slot.geometry;
    return slot.ok;
}

bool SceneLights::derive_wall_geometry(const BuildingWalls& walls, uint32_t building, uint32_t wall,
                                       WallGeometry* out) const {
    const Building& b = scene_->buildings[building];
    if (wall >= walls.count()) return false;
    Vec2 p, q;
    walls.wall(wall, &p, &q);
    if (p == q) return false;
    out->layout = make_wall_layout(facades_, walls.input(wall));
    out->frame = wall_frame(p, q, building_bases_[building] + b.min_height);
    out->building_key = facade_building_key(b);
    out->wall = wall;
    return true;
}

// A lit window's share of its strip's light: its mean radiance (luminance) times its pane
// area; 0 when the window is dark.
double SceneLights::window_weight(const WallGeometry& g, int floor, int slot) const {
    if (!window_lit(facades_, g.building_key, g.wall, g.layout, floor, slot, options_.lit_windows)) return 0;
    return lit_window_weight(g, floor, slot);
}

double SceneLights::lit_window_weight(const WallGeometry& g, int floor, int slot) const {
    const bool shop = cell_kind(g.layout, floor, slot) == CellKind::Shop;
    const uint64_t key = window_key(facades_.seed, g.building_key, g.wall, floor, slot);
    // The opening's size from the rules' own rectangles (cheaper than building the cell's panes).
    const CellKind kind = cell_kind(g.layout, floor, slot);
    const CellRect r = kind == CellKind::Shop      ? g.layout.shop_window()
                        : kind == CellKind::Balcony ? g.layout.door
                                                    : g.layout.window;
    return window_base_luminance(key, shop) * kWindowPatternMean * (r.u1 - r.u0) * (r.v1 - r.v0);
}

WindowPoint SceneLights::window_point(const WallGeometry& g, int floor, int slot, Vec3 position) const {
    WindowPoint w;
    w.shop = cell_kind(g.layout, floor, slot) == CellKind::Shop;
    w.key = window_key(facades_.seed, g.building_key, g.wall, floor, slot);
    const Pane pane = window_pane(g.layout, floor, slot);
    const Vec3 local = g.frame.point_to_local(position);
    w.s = std::clamp((local.x - pane.u0) / (pane.u1 - pane.u0), 0.0, 1.0);
    w.t = std::clamp((local.y - pane.v0) / (pane.v1 - pane.v0), 0.0, 1.0);
    return w;
}

Color WindowPoint::radiance() const { return window_base_radiance(key, shop) * window_pattern(key, s, t); }

double WindowPoint::mean_luminance() const { return window_base_luminance(key, shop) * kWindowPatternMean; }

bool SceneLights::lit_window_at(const Hit& hit) const {
    if (hit.kind != ObjectKind::Building || hit.cell == 0 || !is_pane_material(hit.material)) return false;
    if (!scene_ || !(options_.lit_windows > 0) || hit.object >= scene_->buildings.size()) return false;
    WallGeometry g;
    if (!wall_geometry(hit.object, hit.wall, &g)) return false;
    const int floor = static_cast<int>((hit.cell - 1) >> 16), slot = static_cast<int>((hit.cell - 1) & 0xffff);
    return window_lit(facades_, g.building_key, g.wall, g.layout, floor, slot, options_.lit_windows);
}

void SceneLights::for_each_lit_pane(Vec3 eye, const std::function<bool(const SeenPane&)>& wanted,
                                    const std::function<void(const SeenPane&)>& visit) const {
    // Runs of strips side by side, each wall's geometry derived once from its building's walls
    // (strips are ordered by building and wall).
    constexpr size_t kStripsPerRun = 4096;
    auto gather_run = [&](size_t run, std::vector<SeenPane>& kept) {
        std::optional<BuildingWalls> walls;
        uint32_t building = ~0u, wall = ~0u;
        WallGeometry g;
        Vec3 local;
        bool facing = false;  // the strip's wall is derived and its front faces the eye
        for (size_t i = run * kStripsPerRun, end = std::min(strips_.size(), i + kStripsPerRun); i < end; ++i) {
            const Strip& strip = strips_[i];
            if (strip.building != building || strip.wall != wall) {
                if (strip.building != building) walls.emplace(scene_->buildings[strip.building]);
                building = strip.building;
                wall = strip.wall;
                facing = derive_wall_geometry(*walls, building, wall, &g);
                if (facing) local = g.frame.point_to_local(eye);
                facing = facing && local.z < 0;  // else it sees no pane's front
            }
            if (!facing) continue;
            for (int bit = 0; bit < strip.floor_count * strip.slot_count; ++bit) {
                if (!(strip.lit >> bit & 1)) continue;
                const int floor = strip.first_floor + bit / strip.slot_count;
                const int slot = strip.first_slot + bit % strip.slot_count;
                const Pane pane = visible_pane(window_pane(g.layout, floor, slot), local);
                if (!(pane.area() > 0)) continue;
                const double u0 = pane.u0 - kSeenPaneMargin, u1 = pane.u1 + kSeenPaneMargin;
                const double v0 = pane.v0 - kSeenPaneMargin, v1 = pane.v1 + kSeenPaneMargin;
                const SeenPane seen{strip.building, strip.wall,
                                    static_cast<uint32_t>(floor) * 65536u + static_cast<uint32_t>(slot) + 1,
                                    {g.frame.to_world(u0, v0, pane.at), g.frame.to_world(u1, v0, pane.at),
                                     g.frame.to_world(u1, v1, pane.at), g.frame.to_world(u0, v1, pane.at)}};
                if (wanted(seen)) kept.push_back(seen);
            }
        }
    };
    // The wanted panes visited in order, a batch of runs at a time: a metropolis seen from above
    // wants millions, and all of them at once would hold hundreds of megabytes.
    constexpr size_t kRunsPerBatch = 64;
    const size_t runs = (strips_.size() + kStripsPerRun - 1) / kStripsPerRun;
    std::vector<std::vector<SeenPane>> kept(std::min(runs, kRunsPerBatch));
    for (size_t first = 0; first < runs; first += kRunsPerBatch) {
        const size_t count = std::min(kRunsPerBatch, runs - first);
        tbb::parallel_for(size_t{0}, count, [&](size_t i) { gather_run(first + i, kept[i]); });
        for (size_t i = 0; i < count; ++i) {
            for (const SeenPane& pane : kept[i]) visit(pane);
            kept[i].clear();
        }
    }
}

int64_t SceneLights::strip_light(const Hit& hit) const {
    const int floor = static_cast<int>((hit.cell - 1) >> 16), slot = static_cast<int>((hit.cell - 1) & 0xffff);
    // Strips are ordered by (building, wall, first floor, first slot), each wall's on a regular grid.
    const auto key = std::make_tuple(hit.object, hit.wall, floor / kFloorsPerStrip * kFloorsPerStrip,
                                     slot / kSlotsPerStrip * kSlotsPerStrip);
    auto order = [](const Strip& s) { return std::make_tuple(s.building, s.wall, int(s.first_floor), int(s.first_slot)); };
    const auto at = std::lower_bound(strips_.begin(), strips_.end(), key, [&](const Strip& s, const auto& k) { return order(s) < k; });
    if (at == strips_.end() || order(*at) != key) return -1;
    return static_cast<int64_t>(lamps_.size() + (at - strips_.begin()));
}

Color SceneLights::emitted(const Hit& hit) const {
    if (hit.kind == ObjectKind::Lamp) return hit.material == kLampGlobe && !lamps_.empty() ? lamp_radiance_ : Color{};
    if (!lit_window_at(hit)) return {0, 0, 0};
    WallGeometry g;
    wall_geometry(hit.object, hit.wall, &g);
    const int floor = static_cast<int>((hit.cell - 1) >> 16), slot = static_cast<int>((hit.cell - 1) & 0xffff);
    return window_point(g, floor, slot, hit.position).radiance();
}

bool SceneLights::sample_lamp(const Lamp& lamp, Vec3 p, double u1, double u2, LightSample* out) const {
    const Vec3 c{lamp.center[0], lamp.center[1], lamp.center[2]};
    const double r = lamp.radius;
    const Vec3 to_center = c - p;
    const double d = length(to_center);
    if (!(d > r * 1.0001)) return false;
    const double one_minus_cos = one_minus_cos_sphere(r, d);
    const Vec3 dir = sample_cone(to_center * (1 / d), 1 - one_minus_cos, u1, u2);
    // Nearest intersection with the sphere (the tangent point if rounding misses it).
    const Vec3 oc = p - c;
    const double b = dot(oc, dir);
    const Vec3 f = oc - dir * b;
    const double disc = r * r - dot(f, f);
    const double t = disc > 0 ? -b - std::sqrt(disc) : -b;
    if (!(t > 0)) return false;
    out->direction = dir;
    out->distance = t;
    out->position = p + dir * t;
    out->window = false;
    out->lamp_radiance = lamp_radiance_;
    out->pdf = 1 / (2 * kPi * one_minus_cos);
    return true;
}

double SceneLights::lamp_pdf(const Lamp& lamp, Vec3 p) const {
    const Vec3 c{lamp.center[0], lamp.center[1], lamp.center[2]};
    const double d = length(c - p);
    if (!(d > lamp.radius * 1.0001)) return 0;
    return 1 / (2 * kPi * one_minus_cos_sphere(lamp.radius, d));
}

bool SceneLights::sample(Vec3 p, Vec3 n, const double u[4], LightSample* out) const {
    uint32_t light;
    double pmf;
    if (!choose_light(p, n, u[0], &light, &pmf)) return false;
    if (light < lamps_.size()) {
        if (!sample_lamp(lamps_[light], p, u[1], u[2], out)) return false;
        out->pdf *= pmf;
        return true;
    }
    // A strip of windows: one lit window in proportion to its power (its weight: the strip's
    // total weight is known, so the chance needs no sum over the strip), then a point on the
    // part of its pane p can see (the rest is behind the reveals: its samples would all be blocked).
    const Strip& strip = strips_[light - lamps_.size()];
    WallGeometry g;
    if (!wall_geometry(strip.building, strip.wall, &g)) return false;
    int cells[kFloorsPerStrip * kSlotsPerStrip], count = 0;
    for (int bit = 0; bit < strip.floor_count * strip.slot_count; ++bit)
        if (strip.lit >> bit & 1) cells[count++] = bit;
    auto floor_of = [&](int i) { return strip.first_floor + cells[i] / strip.slot_count; };
    auto slot_of = [&](int i) { return strip.first_slot + cells[i] % strip.slot_count; };
    const int chosen = choose_in_proportion(count, strip.max_weight, kRejectionRounds, u[3], [&](int i) {
        return lit_window_weight(g, floor_of(i), slot_of(i));
    });
    if (chosen < 0) return false;
    const int floor = floor_of(chosen), slot = slot_of(chosen);
    const double weight = lit_window_weight(g, floor, slot);
    const Pane pane = visible_pane(window_pane(g.layout, floor, slot), g.frame.point_to_local(p));
    if (!(pane.area() > 0)) return false;  // p sees none of it: no light from it reaches p
    const Vec3 position = g.frame.to_world(pane.u0 + u[1] * (pane.u1 - pane.u0), pane.v0 + u[2] * (pane.v1 - pane.v0),
                                           pane.at);
    const Vec3 to = position - p;
    const double distance = length(to);
    if (!(distance > 0)) return false;
    const Vec3 dir = to * (1 / distance);
    const double cos_light = dot(dir, g.frame.w_axis);  // the pane faces -w: light leaves towards -w
    if (!(cos_light > 0)) return false;
    out->position = position;
    out->direction = dir;
    out->distance = distance;
    out->window = true;
    out->window_point = window_point(g, floor, slot, position);
    out->pdf = pmf * (weight / strip.weight) / pane.area() * distance * distance / cos_light;
    return true;
}

double SceneLights::pdf(Vec3 p, Vec3 n, const Hit& hit) const {
    if (hit.kind == ObjectKind::Lamp) {
        if (hit.material != kLampGlobe || hit.object >= lamps_.size()) return 0;
        return light_pmf(p, n, hit.object) * lamp_pdf(lamps_[hit.object], p);
    }
    if (!lit_window_at(hit)) return 0;
    const int64_t light = strip_light(hit);
    if (light < 0) return 0;
    const Strip& strip = strips_[light - lamps_.size()];
    WallGeometry g;
    if (!wall_geometry(strip.building, strip.wall, &g)) return 0;
    const int floor = static_cast<int>((hit.cell - 1) >> 16), slot = static_cast<int>((hit.cell - 1) & 0xffff);
    const Vec3 to = hit.position - p;
    const double distance2 = dot(to, to);
    const double cos_light = dot(to * (1 / std::sqrt(distance2)), g.frame.w_axis);
    if (!(cos_light > 0)) return 0;
    const Pane visible = visible_pane(window_pane(g.layout, floor, slot), g.frame.point_to_local(p));
    if (!(visible.area() > 0)) return 0;  // a window p cannot see (rounding at the edge of its opening)
    return light_pmf(p, n, static_cast<uint32_t>(light)) * (lit_window_weight(g, floor, slot) / strip.weight) /
           visible.area() * distance2 / cos_light;
}

}  // namespace citygen
