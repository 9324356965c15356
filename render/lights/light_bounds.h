// What the light BVH knows about a light or a cluster of lights (pbrt-v4's LightBounds, after
// Conty & Kulla 2018): spatial bounds, emitted power, and an orientation cone (axis w, the
// spread of emitter normals theta_o and the emission angle theta_e around each normal).
#pragma once

#include <cmath>

#include "common/geometry.h"

namespace citygen {

struct LightBounds {
    float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
    float w[3] = {0, 0, 1};
    float phi = 0;            // power (luminance-weighted), any consistent unit
    float cos_theta_o = 1;    // normals lie within theta_o of w
    float cos_theta_e = 0;    // each normal emits within theta_e of itself
    bool two_sided = false;
    // w is known to be its own normalization (set_axis(axis()) would not change it): the joins
    // that keep a cluster's axis then skip the square root and division that would confirm it.
    bool axis_settled = false;

    Vec3 min() const { return {lo[0], lo[1], lo[2]}; }
    Vec3 max() const { return {hi[0], hi[1], hi[2]}; }
    Vec3 centroid() const { return (min() + max()) * 0.5; }
    Vec3 axis() const { return {w[0], w[1], w[2]}; }
    void set_box(Vec3 a, Vec3 b);
    void set_axis(Vec3 v);
    void set_axis_up();  // set_axis({0, 0, 1}) without the arithmetic
    void settle_axis();  // set_axis(axis()), once
    // *this = union_of(*this, b), without a copy (the split search joins millions of lights).
    void join(const LightBounds& b);

};

// A shading point as importance() reads it: position and normal in float, converted once per
// descent rather than at every node.
struct LightQuery {
    float p[3], n[3];
    bool has_normal;  // false: a point in a medium, light from all directions counts
    LightQuery(Vec3 point, Vec3 normal)
        : p{float(point.x), float(point.y), float(point.z)},
          n{float(normal.x), float(normal.y), float(normal.z)},
          has_normal(normal.x != 0 || normal.y != 0 || normal.z != 0) {}
};

// A node of the 4-wide light BVH: the bounds of up to four child clusters side by side, one
// per lane, so that importance() evaluates all four at once with SIMD (a binary tree evaluates
// two children per level over twice the levels: as many evaluations, each alone). Per lane:
// the box's centre and half extents, the cone axis w, the power (0: an empty lane) and
// cos theta_o. The sphere around each box and the cone's sine are worked out at each evaluation.
// Our emitters are one-sided panes lighting the hemisphere around their normal or spheres
// (globes), so theta_e is 90 degrees: bounds that emit wider (two-sided, theta_e > 90) are kept
// as emitting in every direction (conservative).
struct alignas(16) LightBounds4 {
    float cx[4], cy[4], cz[4], hx[4], hy[4], hz[4];
    float wx[4], wy[4], wz[4], phi[4], cos_theta_o[4];

    LightBounds4();                             // four empty lanes
    void set(int lane, const LightBounds& b);

    // How much each cluster may light point p with surface normal n (n = 0: a point in a medium,
    // light from all directions counts), as two bounds: `most` with the cluster's nearest point
    // (at least kNearest away), `least` with its farthest. Both are power x orientation bound x
    // surface-cosine bound / distance^2 (Conty & Kulla 2018; pbrt-v4's LightBounds::Importance
    // uses the centre's distance instead) x a visibility prior, kReach^2 / (kReach^2 +
    // distance^2). Zero only where no light of the cluster can arrive (behind every emitter, or
    // below the surface's horizon): sampling stays unbiased.
    void importance(const LightQuery& q, float most[4], float least[4]) const;
    static constexpr float kNearest = 0.1f;  // metres: closer than any shading point to a light's centre
    // Metres. In a city the buildings between a point and a light hide it more often the farther
    // it is, which the bounds cannot know; the prior halves a cluster's importance at kReach.
    // Chosen leaving one of four night views of three cities out (docs/bench/2026-12-night-panes.md).
    static constexpr float kReach = 60.f;
};

// The bounds of two clusters together (cones joined as in pbrt-v4's DirectionCone Union).
LightBounds union_of(const LightBounds& a, const LightBounds& b);

}  // namespace citygen
