#include "render/lights/window_glow.h"

#include <algorithm>
#include <cmath>

#include "common/rng.h"
#include "render/lights/photometry.h"

namespace citygen {

namespace {
// Luminance of a lit window seen from the street, cd/m^2 (curtained rooms ~5-30, shops more).
constexpr double kWindowNits = 15, kShopNits = 60;
double fade(double t) { return t * t * t * (t * (t * 6 - 15) + 10); }
}  // namespace

uint64_t window_key(uint64_t seed, uint64_t building_key, uint32_t wall_index, int floor, int slot) {
    return hash_keys(seed, building_key, wall_index, static_cast<uint64_t>(floor) << 32 | static_cast<uint32_t>(slot),
                     0x6c0e);
}

Pane window_pane(const WallLayout& layout, int floor, int slot) {
    // The pane fills the cell's opening at the bottom of the recess (cell_rects' layer 3), read
    // without building the cell's other rectangles: light sampling asks for every window of a strip.
    const CellRect r = cell_opening(layout, floor, slot);
    return {r.u0, r.u1, r.v0, r.v1, layout.recess};
}

Pane visible_pane(const Pane& pane, Vec3 local) {
    if (!(local.z < 0)) return pane;  // not in front of the facade plane: no claim
    // A point of the pane is seen only through the opening, the pane's own rectangle at w = 0:
    // project the opening's edges from `local` onto the pane's plane (scale s > 1 about local).
    const double s = (pane.at - local.z) / -local.z;
    Pane v = pane;
    v.u0 = std::max(pane.u0, local.x + (pane.u0 - local.x) * s);
    v.u1 = std::min(pane.u1, local.x + (pane.u1 - local.x) * s);
    v.v0 = std::max(pane.v0, local.y + (pane.v0 - local.y) * s);
    v.v1 = std::min(pane.v1, local.y + (pane.v1 - local.y) * s);
    if (!(v.u1 > v.u0 && v.v1 > v.v0)) v.u1 = v.u0, v.v1 = v.v0;
    return v;
}

double window_base_luminance(uint64_t key, bool shop) {
    const double u = hash_to_unit(mix64(key + 2));
    const double nits = (shop ? kShopNits : kWindowNits) * (0.35 + 1.3 * u * u);
    return nits / kNitsPerRadianceUnit;
}

Color window_base_radiance(uint64_t key, bool shop) {
    const double kelvin = shop ? 3000 + 1500 * hash_to_unit(mix64(key + 1)) : 2300 + 1300 * hash_to_unit(mix64(key + 1));
    return blackbody_color(kelvin) * window_base_luminance(key, shop);
}

double perlin_noise(uint64_t key, double x, double y) {
    const double fx = std::floor(x), fy = std::floor(y);
    const int64_t ix = static_cast<int64_t>(fx), iy = static_cast<int64_t>(fy);
    const double dx = x - fx, dy = y - fy;
    auto corner = [&](int64_t cx, int64_t cy, double ox, double oy) {
        const double angle = 2 * kPi * hash_to_unit(hash_keys(key, static_cast<uint64_t>(cx), static_cast<uint64_t>(cy)));
        return std::cos(angle) * ox + std::sin(angle) * oy;
    };
    const double n00 = corner(ix, iy, dx, dy), n10 = corner(ix + 1, iy, dx - 1, dy);
    const double n01 = corner(ix, iy + 1, dx, dy - 1), n11 = corner(ix + 1, iy + 1, dx - 1, dy - 1);
    const double sx = fade(dx), sy = fade(dy);
    const double a = n00 + (n10 - n00) * sx, b = n01 + (n11 - n01) * sx;
    return a + (b - a) * sy;
}

double window_pattern(uint64_t key, double s, double t) {
    // Two octaves across the pane: a soft lamp-lit glow with darker folds.
    const double ox = 100 * hash_to_unit(mix64(key + 3)), oy = 100 * hash_to_unit(mix64(key + 4));
    const double n = perlin_noise(key, 2.2 * s + ox, 1.6 * t + oy) + 0.5 * perlin_noise(key + 7, 5 * s + ox, 4 * t + oy);
    return std::clamp(kWindowPatternMean + 0.6 * n, 0.2, 1.0);
}

}  // namespace citygen
