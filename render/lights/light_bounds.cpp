#include "light_bounds.h"

#include <algorithm>
#include <cmath>

namespace citygen {

namespace {


double safe_acos(double x) { return std::acos(std::clamp(x, -1.0, 1.0)); }

// v rotated by `angle` around the unit axis k (Rodrigues).
Vec3 rotate(Vec3 v, Vec3 k, double angle) {
    const double c = std::cos(angle), s = std::sin(angle);
    return v * c + cross(k, v) * s + k * (dot(k, v) * (1 - c));
}

}  // namespace

void LightBounds::set_box(Vec3 a, Vec3 b) {
    for (int i = 0; i < 3; ++i) {
        lo[i] = static_cast<float>(std::min(a[i], b[i]));
        hi[i] = static_cast<float>(std::max(a[i], b[i]));
    }
}

void LightBounds::set_axis(Vec3 v) {
    v = normalize(v);
    w[0] = static_cast<float>(v.x);
    w[1] = static_cast<float>(v.y);
    w[2] = static_cast<float>(v.z);
}

CompactLightBounds::CompactLightBounds(const LightBounds& b) {
    for (int i = 0; i < 3; ++i) {
        center[i] = 0.5f * (b.lo[i] + b.hi[i]);
        half[i] = 0.5f * (b.hi[i] - b.lo[i]);
        w[i] = b.w[i];
    }
    phi = b.phi;
    // Two-sided or wider than a hemisphere: any direction (conservative). Narrower: the
    // hemisphere (conservative too).
    cos_theta_o = b.two_sided || b.cos_theta_e < 0 ? -1 : b.cos_theta_o;
}

void CompactLightBounds::importance(const LightQuery& q, double* most, double* least) const {
    *most = *least = 0;
    // Float throughout: two of these per level of every descent.
    const float tx = q.p[0] - center[0], ty = q.p[1] - center[1], tz = q.p[2] - center[2];  // towards p
    const float nx = q.n[0], ny = q.n[1], nz = q.n[2];
    const float hx = half[0], hy = half[1], hz = half[2];
    const float dist2 = tx * tx + ty * ty + tz * tz;
    const float dist = std::sqrt(dist2);
    const float inv_dist = dist > 0 ? 1 / dist : 0;
    const float wx = dist > 0 ? tx * inv_dist : 0, wy = dist > 0 ? ty * inv_dist : 0, wz = dist > 0 ? tz * inv_dist : 1;
    // The cone of directions from p that the bounds' sphere subtends (all of them from inside).
    const float radius = this->radius();
    const bool inside = dist2 <= radius * radius;
    const float sin_b = inside ? 0 : radius * inv_dist;
    const float cos_b = inside ? -1 : std::sqrt(std::max(0.f, 1 - sin_b * sin_b));
    // The box itself, tighter than its sphere up close (a wall's own windows from a point on the
    // wall): wholly behind emitters that all face w, or wholly below the horizon of n, it sends p
    // nothing. The extremes of a linear function over a box are centre +- half extents.
    if (cos_theta_o >= 1 &&
        w[0] * tx + w[1] * ty + w[2] * tz + hx * std::fabs(w[0]) + hy * std::fabs(w[1]) + hz * std::fabs(w[2]) <= 0)
        return;
    if (q.has_normal && -(tx * nx + ty * ny + tz * nz) + hx * std::fabs(nx) + hy * std::fabs(ny) + hz * std::fabs(nz) <= 0)
        return;
    float cos_p = 1;  // normals pointing everywhere (any cluster holding a lamp's globe): no bound
    if (cos_theta_o > -1) {
        const float cos_w = w[0] * wx + w[1] * wy + w[2] * wz;
        const float sin_w = std::sqrt(std::max(0.f, 1 - cos_w * cos_w));
        // theta_x = max(0, theta_w - theta_o), then cos(max(0, theta_x - theta_b)).
        const bool within_o = cos_w > cos_theta_o;
        const float sin_theta_o = std::sqrt(std::max(0.f, 1 - cos_theta_o * cos_theta_o));
        const float cos_x = within_o ? 1 : cos_w * cos_theta_o + sin_w * sin_theta_o;
        const float sin_x = within_o ? 0 : sin_w * cos_theta_o - cos_w * sin_theta_o;
        cos_p = cos_x > cos_b ? 1 : cos_x * cos_b + sin_x * sin_b;
        if (cos_p <= 0) return;  // theta_e = 90 degrees
    }
    float factor = phi * cos_p;
    if (q.has_normal) {
        // Our surfaces only reflect (glass is never sampled): a cluster wholly below the
        // horizon of n cannot light p.
        const float cos_i = -(wx * nx + wy * ny + wz * nz);
        const float sin_i = std::sqrt(std::max(0.f, 1 - cos_i * cos_i));
        const float bound = cos_i > cos_b ? 1 : cos_i * cos_b + sin_i * sin_b;
        if (!(bound > 0)) return;
        factor *= bound;
    }
    if (!(factor > 0)) return;
    // Nearest point of the box (no nearer than kNearest) and farthest point of the sphere.
    const float ex = std::max(std::fabs(tx) - hx, 0.f), ey = std::max(std::fabs(ty) - hy, 0.f),
                ez = std::max(std::fabs(tz) - hz, 0.f);
    const float near2 = std::max(ex * ex + ey * ey + ez * ez, kNearest * kNearest);
    const float far = dist + radius;
    *most = double(factor) / near2;
    *least = double(factor) / std::max(far * far, near2);
}

LightBounds union_of(const LightBounds& a, const LightBounds& b) {
    if (a.phi <= 0) return b;
    if (b.phi <= 0) return a;
    LightBounds u;
    for (int i = 0; i < 3; ++i) {
        u.lo[i] = std::min(a.lo[i], b.lo[i]);
        u.hi[i] = std::max(a.hi[i], b.hi[i]);
    }
    u.phi = a.phi + b.phi;
    u.cos_theta_e = std::min(a.cos_theta_e, b.cos_theta_e);
    u.two_sided = a.two_sided || b.two_sided;
    // Join the normal cones (the common cases first: a whole sphere such as a lamp's globe, or
    // two parallel walls).
    if (a.cos_theta_o <= -1 || b.cos_theta_o <= -1) {
        u.set_axis({0, 0, 1});
        u.cos_theta_o = -1;
        return u;
    }
    if (a.w[0] == b.w[0] && a.w[1] == b.w[1] && a.w[2] == b.w[2]) {
        u.set_axis(a.axis());
        u.cos_theta_o = std::min(a.cos_theta_o, b.cos_theta_o);
        return u;
    }
    const double theta_a = safe_acos(a.cos_theta_o), theta_b = safe_acos(b.cos_theta_o);
    const double theta_d = safe_acos(dot(a.axis(), b.axis()));
    if (std::min(theta_d + theta_b, kPi) <= theta_a) {
        u.set_axis(a.axis());
        u.cos_theta_o = a.cos_theta_o;
    } else if (std::min(theta_d + theta_a, kPi) <= theta_b) {
        u.set_axis(b.axis());
        u.cos_theta_o = b.cos_theta_o;
    } else {
        const double theta_o = (theta_a + theta_d + theta_b) / 2;
        const Vec3 wr = cross(a.axis(), b.axis());
        if (theta_o >= kPi || dot(wr, wr) == 0) {
            u.set_axis({0, 0, 1});
            u.cos_theta_o = -1;
        } else {
            u.set_axis(rotate(a.axis(), normalize(wr), theta_o - theta_a));
            u.cos_theta_o = static_cast<float>(std::max(-1.0, std::cos(theta_o) - 1e-5));  // float rounding: never narrower
        }
    }
    return u;
}

}  // namespace citygen
