#include "render/geometry/stair_geometry.h"

#include <algorithm>
#include <cmath>

#include "common/ground.h"

namespace citygen {

namespace {

// The part of a convex ring where lo <= dot(p - o, u) <= hi (Sutherland-Hodgman, one side at a
// time); the points on each cut are computed from the same edge in both treads beside it.
Ring clip_between(const Ring& ring, Vec2 o, Vec2 u, double lo, double hi) {
    const auto cut = [&](const Ring& in, double s, double sign) {
        Ring out;
        for (size_t k = 0, n = in.size(); k < n; ++k) {
            const Vec2 p = in[k], q = in[(k + 1) % n];
            const double dp = sign * (dot(p - o, u) - s), dq = sign * (dot(q - o, u) - s);
            if (dp >= 0) out.push_back(p);
            if ((dp < 0) != (dq < 0)) out.push_back(p + (q - p) * (dp / (dp - dq)));
        }
        Ring clean;
        for (Vec2 p : out)
            if (clean.empty() || !(p == clean.back())) clean.push_back(p);
        while (clean.size() > 1 && clean.front() == clean.back()) clean.pop_back();
        return clean;
    };
    return cut(cut(ring, lo, +1), hi, -1);
}

// The lowest drawn ground under the segment a-b: the field's surface is linear between the
// points where the segment crosses the cells' lines and diagonals.
double lowest_ground(const Scene& scene, Vec2 a, Vec2 b) {
    double z = std::min(ground_height(scene, a.x, a.y), ground_height(scene, b.x, b.y));
    for (double t : field_line_crossings(scene.terrain, a, b)) {
        const Vec2 p = a + (b - a) * t;
        z = std::min(z, ground_height(scene, p.x, p.y));
    }
    return z;
}

// The vertical rectangle under the edge a->b of a counter-clockwise outline, from z0 up to z1,
// facing out.
PlanarFace wall(Vec2 a, Vec2 b, double z0, double z1, uint16_t material) {
    return {{{a.x, a.y, z0}, {b.x, b.y, z0}, {b.x, b.y, z1}, {a.x, a.y, z1}}, material};
}

}  // namespace

std::vector<PlanarFace> stair_faces(const Scene& scene, const StairPlan& plan, const Ring& quad, double lift,
                                    uint16_t material) {
    std::vector<PlanarFace> faces;
    if (quad.size() < 3 || plan.steps <= 0) return faces;
    Ring ring = quad;
    if (signed_area(ring) < 0) std::reverse(ring.begin(), ring.end());
    const Vec2 o = plan.low, u = normalize(plan.high - plan.low);
    const double tread = plan.run() / plan.steps, rise = plan.rise();
    // A point is on a cut when it is this close to it (the cut's own points are exact to rounding).
    const double on_cut = 1e-9 * (1 + plan.run());
    for (int k = 0; k < plan.steps; ++k) {
        // The strip beyond the ends' centres (a mitred corner) belongs to the first or last tread.
        const double lo = k == 0 ? -1e300 : k * tread, hi = k + 1 == plan.steps ? 1e300 : (k + 1) * tread;
        const Ring outline = clip_between(ring, o, u, lo, hi);
        if (outline.size() < 3) continue;
        const double z = plan.z_low + lift + (k + 1) * rise;
        PlanarFace top{{}, material};
        for (Vec2 p : outline) top.points.push_back({p.x, p.y, z});
        faces.push_back(std::move(top));
        for (size_t e = 0, n = outline.size(); e < n; ++e) {
            const Vec2 a = outline[e], b = outline[(e + 1) % n];
            const auto on = [&](double s) {
                return std::fabs(dot(a - o, u) - s) < on_cut && std::fabs(dot(b - o, u) - s) < on_cut;
            };
            if (k > 0 && on(lo)) {
                faces.push_back(wall(a, b, z - rise, z, material));  // the riser up from the tread below
                continue;
            }
            if (k + 1 < plan.steps && on(hi)) continue;  // the next tread's riser
            const double bottom = lowest_ground(scene, a, b) - kStairFooting;
            if (bottom < z) faces.push_back(wall(a, b, bottom, z, material));
        }
    }
    return faces;
}

namespace {

template <class Geometry>
bool add_stair_to(const Scene& scene, uint32_t index, double lift, uint16_t material, Geometry& geometry) {
    StairPlan plan;
    if (!plan_stair(scene, scene.paths[index], &plan)) return false;
    add_faces(stair_faces(scene, plan, scene.paths[index].quad, lift, material), index, geometry);
    return true;
}

}  // namespace

bool add_stair(const Scene& scene, uint32_t index, double lift, uint16_t material, TriangleMesh& mesh) {
    return add_stair_to(scene, index, lift, material, mesh);
}

bool add_stair(const Scene& scene, uint32_t index, double lift, uint16_t material, ProceduralGeometry& geometry) {
    return add_stair_to(scene, index, lift, material, geometry);
}

}  // namespace citygen
