// How a lit window looks (as in the thesis named in README): each lit window its own warm colour
// and brightness, its pane's emission varied by a per-window Perlin-noise pattern (curtains,
// lamps in the room).
// Pure functions of the window's hash, so both geometry modes and the light sampler agree.
#pragma once

#include <cstdint>

#include "render/facade/facade.h"
#include "render/materials/materials.h"

namespace citygen {

// The key of one window: (seed, building key, wall index, cell).
uint64_t window_key(uint64_t seed, uint64_t building_key, uint32_t wall_index, int floor, int slot);

// The pane of cell (floor, slot) in wall-local coordinates: [u0, u1] x [v0, v1] at w = at,
// facing -w (out of the building). The facade rules' own rectangle (cell_rects, layer 3).
struct Pane {
    double u0, u1, v0, v1, at;
    double area() const { return (u1 - u0) * (v1 - v0); }
};
Pane window_pane(const WallLayout& layout, int floor, int slot);

// The part of `pane` a point sees through the window's opening, for a point at wall-local
// `local` (u, v, w; w < 0 in front of the facade). The pane sits `at` deep in its recess, so the
// reveals hide a band of it from an oblique point: a segment to the hidden part crosses the
// facade plane outside the opening and must enter the recess through a reveal. Empty (zero
// area) when nothing shows; the whole pane for a point not in front of the facade plane.
Pane visible_pane(const Pane& pane, Vec3 local);

// Mean radiance of a lit window (before its noise pattern), in render units, and its luminance.
Color window_base_radiance(uint64_t key, bool shop);
double window_base_luminance(uint64_t key, bool shop);

// The window's noise pattern at (s, t) in [0, 1]^2 across the pane: in [0.2, 1.0], mean ~0.6.
double window_pattern(uint64_t key, double s, double t);
constexpr double kWindowPatternMean = 0.6;

// 2D Perlin gradient noise (about -0.7..0.7), lattice gradients hashed from `key`.
double perlin_noise(uint64_t key, double x, double y);

}  // namespace citygen
