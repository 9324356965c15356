#include "render/geometry/lamp_shape.h"

#include <algorithm>
#include <cmath>

#include "render/geometry/ground.h"

namespace citygen {

namespace {
// Sizes of a common post-top lantern, metres.
constexpr double kPoleRadius = 0.06;
constexpr double kGlobeRadius = 0.22;
constexpr double kCapRadius = 0.28;
constexpr double kCapThickness = 0.08;
constexpr double kMinHeight = 1.0 + 2 * kGlobeRadius;
}  // namespace

double lamp_ground(const StandingSurface& surface, const Lamp& lamp) {
    return surface.height({lamp.position.x, lamp.position.y});
}

LampShape lamp_shape(const Lamp& lamp, double ground_z) {
    LampShape s;
    s.base = {lamp.position.x, lamp.position.y, ground_z + lamp.position.z};
    const double height = std::max(lamp.height, kMinHeight);
    s.globe_radius = kGlobeRadius;
    s.globe_center = {s.base.x, s.base.y, s.base.z + height - kGlobeRadius};
    s.pole_radius = kPoleRadius;
    s.pole_top = s.globe_center.z - kGlobeRadius + 0.02;  // just into the globe: no gap at the seam
    s.cap_radius = kCapRadius;
    s.cap_bottom = s.base.z + height;
    s.cap_top = s.cap_bottom + kCapThickness;
    return s;
}

}  // namespace citygen

namespace citygen {

namespace {

// Keeps the nearest of the candidate hits.
struct Nearest {
    double tmin, tmax;
    LampHit* hit;
    bool found = false;
    void offer(double t, Vec3 normal, LampPart part) {
        if (!(t >= tmin && t <= tmax)) return;
        if (found && t >= hit->t) return;
        found = true;
        hit->t = t;
        hit->normal = normal;
        hit->part = part;
    }
};

// Side of the vertical cylinder of radius r around (cx, cy) between z0 and z1 (both roots: the
// inside of the cap rim is never seen, but a ray starting inside must still find the wall).
void vertical_cylinder(Vec3 o, Vec3 d, double cx, double cy, double r, double z0, double z1, LampPart part,
                       Nearest& nearest) {
    const double ox = o.x - cx, oy = o.y - cy;
    const double a = d.x * d.x + d.y * d.y;
    if (a <= 0) return;
    const double b = ox * d.x + oy * d.y, c = ox * ox + oy * oy - r * r;
    const double disc = b * b - a * c;
    if (disc < 0) return;
    const double root = std::sqrt(disc);
    // Stable roots: q = -(b + sign(b) root), t = q / a and c / q.
    const double q = -(b + std::copysign(root, b));
    double ts[2] = {q / a, q != 0 ? c / q : q / a};
    for (double t : ts) {
        const double z = o.z + d.z * t;
        if (z < z0 || z > z1) continue;
        const double px = ox + d.x * t, py = oy + d.y * t;
        nearest.offer(t, normalize(Vec3{px, py, 0}), part);
    }
}

// Horizontal disk of radius r around (cx, cy) at height z, facing up (+1) or down (-1).
void horizontal_disk(Vec3 o, Vec3 d, double cx, double cy, double r, double z, int facing, LampPart part,
                     Nearest& nearest) {
    if (d.z == 0) return;
    const double t = (z - o.z) / d.z;
    const double px = o.x + d.x * t - cx, py = o.y + d.y * t - cy;
    if (px * px + py * py > r * r) return;
    nearest.offer(t, {0, 0, double(facing)}, part);
}

void sphere(Vec3 o, Vec3 d, Vec3 center, double r, LampPart part, Nearest& nearest) {
    const Vec3 oc = o - center;
    const double b = dot(oc, d), c = dot(oc, oc) - r * r;
    // Distance-based discriminant (Hearn-Baker / Ray Tracing Gems 7): accurate far from the sphere.
    const Vec3 f = oc - d * b;
    const double disc = r * r - dot(f, f);
    if (disc < 0) return;
    const double q = -(b + std::copysign(std::sqrt(disc), b));
    double ts[2] = {c / q, q};
    if (q == 0) ts[0] = 0;
    for (double t : ts) nearest.offer(t, normalize(o + d * t - center), part);
}

}  // namespace

bool intersect_lamp(const LampShape& lamp, Vec3 origin, Vec3 direction, double tmin, double tmax, LampHit* hit) {
    Nearest nearest{tmin, tmax, hit};
    const double cx = lamp.base.x, cy = lamp.base.y;
    vertical_cylinder(origin, direction, cx, cy, lamp.pole_radius, lamp.base.z, lamp.pole_top, LampPart::Pole,
                      nearest);
    sphere(origin, direction, lamp.globe_center, lamp.globe_radius, LampPart::Globe, nearest);
    vertical_cylinder(origin, direction, cx, cy, lamp.cap_radius, lamp.cap_bottom, lamp.cap_top, LampPart::Cap,
                      nearest);
    horizontal_disk(origin, direction, cx, cy, lamp.cap_radius, lamp.cap_top, +1, LampPart::Cap, nearest);
    horizontal_disk(origin, direction, cx, cy, lamp.cap_radius, lamp.cap_bottom, -1, LampPart::Cap, nearest);
    return nearest.found;
}

}  // namespace citygen
