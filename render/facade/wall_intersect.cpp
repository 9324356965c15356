#include "render/facade/wall_intersect.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace citygen {

WallIntersectStats& wall_intersect_stats() {
    static thread_local WallIntersectStats stats;
    return stats;
}

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

// The ray in wall-local coordinates, with what every rectangle test reuses.
struct LocalRay {
    double o[3], d[3], inv[3];
};

LocalRay to_local(const WallFrame& frame, Vec3 origin, Vec3 direction) {
    LocalRay ray;
    Vec3 o = frame.point_to_local(origin), d = frame.direction_to_local(direction);
    for (int i = 0; i < 3; ++i) {
        ray.o[i] = o[i];
        ray.d[i] = d[i];
        ray.inv[i] = d[i] != 0 ? 1.0 / d[i] : kInf;
    }
    return ray;
}

// Free axes of a rectangle, in increasing order (see FacadeRect).
constexpr int kFirstFree[3] = {1, 0, 0};
constexpr int kSecondFree[3] = {2, 2, 1};

// Hit with tmin <= t < *t_best (or <= for the first candidate at tmax); bounds inclusive.
inline bool hit_rect(const FacadeRect& r, const LocalRay& ray, double tmin, double* t_best) {
    const int axis = r.axis;
    if (ray.d[axis] == 0) return false;  // parallel: a zero-thickness rectangle is never hit
    const double t = (r.at - ray.o[axis]) * ray.inv[axis];
    if (!(t >= tmin && t <= *t_best)) return false;
    const double a = ray.o[kFirstFree[axis]] + ray.d[kFirstFree[axis]] * t;
    if (a < r.a0 || a > r.a1) return false;
    const double b = ray.o[kSecondFree[axis]] + ray.d[kSecondFree[axis]] * t;
    if (b < r.b0 || b > r.b1) return false;
    *t_best = t;
    return true;
}

// Clip the ray to [lo, hi] on one axis; false when it never enters.
inline bool clip_axis(const LocalRay& ray, int axis, double lo, double hi, double* t0, double* t1) {
    if (ray.d[axis] == 0) return ray.o[axis] >= lo && ray.o[axis] <= hi;
    double ta = (lo - ray.o[axis]) * ray.inv[axis], tb = (hi - ray.o[axis]) * ray.inv[axis];
    if (ta > tb) std::swap(ta, tb);
    *t0 = std::max(*t0, ta);
    *t1 = std::min(*t1, tb);
    return *t0 <= *t1;
}

struct Found {
    FacadeRect copy;  // cell rectangles live on the walker's stack, so keep the winner
    int floor = -1, slot = -1;
};

// The walk shared by the nearest-hit and any-hit queries. With any_hit it returns at the first
// rectangle found; otherwise the nearest one, with *t_best its distance.
// The margin rectangles around the grid; the nearest hit goes to `found` (the first with any_hit).
inline bool hit_margins(const WallLayout& layout, const LocalRay& ray, double tmin, double* t_best, bool any_hit,
                        Found* found, FacadeRect* rects, WallIntersectStats& stats) {
    bool hit = false;
    const int n = margin_rects(layout, rects);
    stats.rects += static_cast<uint64_t>(n);
    for (int i = 0; i < n; ++i) {
        if (hit_rect(rects[i], ray, tmin, t_best)) {
            hit = true;
            found->copy = rects[i];
            found->floor = found->slot = -1;
            if (any_hit) return true;
        }
    }
    return hit;
}

// The rectangles of one cell, layer by layer in the order the ray meets them: after a layer with
// a hit, later layers can only be farther. A ray parallel to the wall plane has no order: test
// everything.
inline bool hit_cell(const WallLayout& layout, int floor, int slot, const LocalRay& ray, double tmin, double* t_best,
                     bool any_hit, Found* found, FacadeRect* rects, WallIntersectStats& stats) {
    ++stats.cells;
    int layer_end[kCellLayers];
    const int n = cell_rects(layout, floor, slot, rects, layer_end);
    bool cell_hit = false;
    for (int step = 0; step < kCellLayers && !cell_hit; ++step) {
        const int layer = ray.d[2] < 0 ? kCellLayers - 1 - step : step;
        const int begin = layer == 0 ? 0 : layer_end[layer - 1];
        const int end = ray.d[2] == 0 ? n : layer_end[layer];
        for (int i = begin; i < end; ++i) {
            ++stats.rects;
            if (hit_rect(rects[i], ray, tmin, t_best)) {
                cell_hit = true;
                found->copy = rects[i];
                found->floor = floor;
                found->slot = slot;
                if (any_hit) return true;
            }
        }
        if (ray.d[2] == 0) break;
    }
    return cell_hit;
}

bool walk_wall(const WallLayout& layout, const LocalRay& ray, double tmin, double* t_best, bool any_hit,
               Found* found) {
    WallIntersectStats& stats = wall_intersect_stats();
    ++stats.calls;
    FacadeRect rects[kMaxCellRects];

    // 1. Most rays that reach a wall primitive only pass its bounding box: leave unless the ray
    // crosses the wall's own slab (slightly padded so surfaces on its faces are not missed).
    const double pad = 1e-9 * (1.0 + layout.length + layout.height);
    double s0 = tmin, s1 = *t_best;
    if (!clip_axis(ray, 2, layout.w_min() - pad, layout.w_max() + pad, &s0, &s1)) return false;
    if (!clip_axis(ray, 0, -pad, layout.length + pad, &s0, &s1)) return false;
    if (!clip_axis(ray, 1, -pad, layout.height + pad, &s0, &s1)) return false;

    // 2. The plain facade outside the grid: a handful of rectangles on the plane w = 0.
    const bool hit = hit_margins(layout, ray, tmin, t_best, any_hit, found, rects, stats);
    if ((hit && any_hit) || layout.plain()) return hit;

    // 3. Clip to the grid's box.
    double t0 = tmin, t1 = *t_best;
    if (!clip_axis(ray, 0, layout.grid_u0 - pad, layout.grid_u1() + pad, &t0, &t1)) return hit;
    if (!clip_axis(ray, 1, layout.grid_v0 - pad, layout.grid_v1() + pad, &t0, &t1)) return hit;
    if (!clip_axis(ray, 2, layout.w_min() - pad, layout.w_max() + pad, &t0, &t1)) return hit;

    // 4. 2D DDA over (slot, floor) from where the ray enters the box. All geometry of a cell lies
    // inside the cell's (u, v) rectangle, so the first cell with a hit holds the nearest hit.
    const double sw = layout.slot_width, fh = layout.floor_height;
    const double u_enter = ray.o[0] + ray.d[0] * t0, v_enter = ray.o[1] + ray.d[1] * t0;
    int slot = std::clamp(static_cast<int>(std::floor((u_enter - layout.grid_u0) / sw)), 0, layout.slots - 1);
    int floor = std::clamp(static_cast<int>(std::floor((v_enter - layout.grid_v0) / fh)), 0, layout.floors - 1);
    const int slot_step = ray.d[0] > 0 ? 1 : -1, floor_step = ray.d[1] > 0 ? 1 : -1;
    // Distance to the cell boundary the ray leaves through, recomputed (not accumulated) per step.
    auto next_u = [&] {
        if (ray.d[0] == 0) return kInf;
        return (layout.grid_u0 + (slot + (ray.d[0] > 0 ? 1 : 0)) * sw - ray.o[0]) * ray.inv[0];
    };
    auto next_v = [&] {
        if (ray.d[1] == 0) return kInf;
        return (layout.grid_v0 + (floor + (ray.d[1] > 0 ? 1 : 0)) * fh - ray.o[1]) * ray.inv[1];
    };
    double t_u = next_u(), t_v = next_v();
    for (;;) {
        if (hit_cell(layout, floor, slot, ray, tmin, t_best, any_hit, found, rects, stats)) return true;
        if (std::min(t_u, t_v) > std::min(t1, *t_best)) return hit;
        if (t_u < t_v) {
            slot += slot_step;
            if (slot < 0 || slot >= layout.slots) return hit;
            t_u = next_u();
        } else {
            floor += floor_step;
            if (floor < 0 || floor >= layout.floors) return hit;
            t_v = next_v();
        }
    }
}

}  // namespace

bool intersect_wall(const WallLayout& layout, const WallFrame& frame, Vec3 origin, Vec3 direction, double tmin,
                    double tmax, WallHit* hit) {
    const LocalRay ray = to_local(frame, origin, direction);
    double t = tmax;
    Found found;
    if (!walk_wall(layout, ray, tmin, &t, false, &found)) return false;
    const FacadeRect& r = found.copy;
    Vec3 local_normal;
    if (r.axis == 0) local_normal = {double(r.normal_sign), 0, 0};
    if (r.axis == 1) local_normal = {0, double(r.normal_sign), 0};
    if (r.axis == 2) local_normal = {0, 0, double(r.normal_sign)};
    hit->t = t;
    hit->normal = frame.direction_to_world(local_normal);
    hit->local = {ray.o[0] + ray.d[0] * t, ray.o[1] + ray.d[1] * t, ray.o[2] + ray.d[2] * t};
    hit->surface = r.surface;
    hit->floor = found.floor;
    hit->slot = found.slot;
    return true;
}

bool wall_occluded(const WallLayout& layout, const WallFrame& frame, Vec3 origin, Vec3 direction, double tmin,
                   double tmax) {
    const LocalRay ray = to_local(frame, origin, direction);
    double t = tmax;
    Found found;
    return walk_wall(layout, ray, tmin, &t, true, &found);
}

}  // namespace citygen
