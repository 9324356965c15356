#include "light_bounds.h"

#include <algorithm>
#include <cmath>

namespace citygen {

namespace {


double safe_sqrt(double x) { return std::sqrt(std::max(0.0, x)); }
double safe_acos(double x) { return std::acos(std::clamp(x, -1.0, 1.0)); }
// cos(max(0, a - b)) and sin(max(0, a - b)) from the sines and cosines of a and b.
double cos_sub_clamped(double sin_a, double cos_a, double sin_b, double cos_b) {
    return cos_a > cos_b ? 1 : cos_a * cos_b + sin_a * sin_b;
}
double sin_sub_clamped(double sin_a, double cos_a, double sin_b, double cos_b) {
    return cos_a > cos_b ? 0 : sin_a * cos_b - cos_a * sin_b;
}

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

double LightBounds::importance(Vec3 p, Vec3 n) const { return CompactLightBounds(*this).importance(p, n); }

CompactLightBounds::CompactLightBounds(const LightBounds& b) {
    const Vec3 c = b.centroid(), diagonal = b.max() - b.min();
    for (int i = 0; i < 3; ++i) {
        center[i] = static_cast<float>(c[i]);
        w[i] = b.w[i];
    }
    // Rounded outwards a little: the sphere must hold the box.
    radius2 = static_cast<float>(dot(diagonal, diagonal) / 4 * (1 + 1e-5));
    phi = b.phi;
    cos_theta_o = b.two_sided ? -1 : b.cos_theta_o;  // two-sided: any direction (conservative)
    cos_theta_e = b.cos_theta_e;
}

double CompactLightBounds::importance(Vec3 p, Vec3 n) const {
    const Vec3 to_p = p - Vec3{center[0], center[1], center[2]};  // from the cluster towards p
    const double dist2 = dot(to_p, to_p);
    // pbrt-v4: no blow-up near or inside the cluster (distance^2 at least half the diagonal).
    const double d2 = std::max(dist2, std::sqrt(double(radius2)));
    const Vec3 wi = dist2 > 0 ? to_p * (1 / std::sqrt(dist2)) : Vec3{0, 0, 1};
    // The cone of directions from p that the bounds' sphere subtends.
    const double cos_b = dist2 < radius2 ? -1 : safe_sqrt(1 - radius2 / dist2);
    const double sin_b = safe_sqrt(1 - cos_b * cos_b);
    double cos_p = 1;  // normals pointing everywhere (any cluster holding a lamp's globe): no bound
    if (cos_theta_o > -1) {
        const double cos_w = w[0] * wi.x + w[1] * wi.y + w[2] * wi.z;
        const double sin_w = safe_sqrt(1 - cos_w * cos_w);
        const double sin_theta_o = safe_sqrt(1 - double(cos_theta_o) * cos_theta_o);
        const double cos_x = cos_sub_clamped(sin_w, cos_w, sin_theta_o, cos_theta_o);
        const double sin_x = sin_sub_clamped(sin_w, cos_w, sin_theta_o, cos_theta_o);
        cos_p = cos_sub_clamped(sin_x, cos_x, sin_b, cos_b);
        if (cos_p <= cos_theta_e) return 0;
    }
    double importance = phi * cos_p / d2;
    if (n.x != 0 || n.y != 0 || n.z != 0) {
        // Our surfaces only reflect (glass is never sampled): a cluster wholly below the
        // horizon of n cannot light p.
        const double cos_i = -dot(wi, n);
        const double sin_i = safe_sqrt(1 - cos_i * cos_i);
        importance *= std::max(0.0, cos_sub_clamped(sin_i, cos_i, sin_b, cos_b));
    }
    return std::max(importance, 0.0);
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
