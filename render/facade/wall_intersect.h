// Analytic ray/wall intersection: the procedural geometry mode's walls.
//
// Computes the same surfaces as the triangulated wall (facade_mesh.h) without building it:
// the ray is clipped to the wall's slab, then only the facade cells it crosses are visited
// (a 2D DDA over floors x slots in wall-local coordinates) and each visited cell's few
// rectangles are tested. Cost grows with the cells crossed, not with the windows on the wall.
// No allocation; safe to call from Embree callbacks on any thread.
#pragma once

#include "render/facade/facade.h"

namespace citygen {

struct WallHit {
    double t = 0;
    Vec3 normal;                    // world, unit; the rectangle's normal (same as the triangles')
    Vec3 local;                     // wall-local hit point (u, v, w)
    FacadeSurface surface = FacadeSurface::Wall;
    int floor = -1, slot = -1;      // the cell hit, -1 for the margins
};

// Nearest hit with tmin <= t <= tmax; false when the ray misses the wall.
bool intersect_wall(const WallLayout& layout, const WallFrame& frame, Vec3 origin, Vec3 direction, double tmin,
                    double tmax, WallHit* hit);

// True when anything on the wall lies at tmin <= t <= tmax (shadow rays).
bool wall_occluded(const WallLayout& layout, const WallFrame& frame, Vec3 origin, Vec3 direction, double tmin,
                   double tmax);

// Counters for benchmarks: cells visited and rectangles tested by the calls on this thread.
struct WallIntersectStats {
    uint64_t calls = 0, cells = 0, rects = 0;
};
WallIntersectStats& wall_intersect_stats();

}  // namespace citygen
