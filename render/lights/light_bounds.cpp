#include "render/lights/light_bounds.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace citygen {

namespace {

// Four floats, with SSE where there is SSE (every x86-64) and plain lanes elsewhere.
// Comparisons give masks (all bits set where true) for select, & and |.
#if defined(__SSE2__)
struct F4 {
    __m128 v;
    F4(__m128 x) : v(x) {}
    explicit F4(float x) : v(_mm_set1_ps(x)) {}
    static F4 load(const float* p) { return _mm_load_ps(p); }
    void store(float* p) const { _mm_storeu_ps(p, v); }
};
inline F4 operator+(F4 a, F4 b) { return _mm_add_ps(a.v, b.v); }
inline F4 operator-(F4 a, F4 b) { return _mm_sub_ps(a.v, b.v); }
inline F4 operator*(F4 a, F4 b) { return _mm_mul_ps(a.v, b.v); }
inline F4 operator/(F4 a, F4 b) { return _mm_div_ps(a.v, b.v); }
inline F4 operator>(F4 a, F4 b) { return _mm_cmpgt_ps(a.v, b.v); }
inline F4 operator>=(F4 a, F4 b) { return _mm_cmpge_ps(a.v, b.v); }
inline F4 operator<=(F4 a, F4 b) { return _mm_cmple_ps(a.v, b.v); }
inline F4 operator&(F4 a, F4 b) { return _mm_and_ps(a.v, b.v); }
inline F4 operator|(F4 a, F4 b) { return _mm_or_ps(a.v, b.v); }
inline F4 operator!(F4 a) { return _mm_xor_ps(a.v, _mm_castsi128_ps(_mm_set1_epi32(-1))); }
inline F4 select(F4 mask, F4 a, F4 b) { return _mm_or_ps(_mm_and_ps(mask.v, a.v), _mm_andnot_ps(mask.v, b.v)); }
inline F4 sqrt(F4 a) { return _mm_sqrt_ps(a.v); }
inline F4 max(F4 a, F4 b) { return _mm_max_ps(a.v, b.v); }
inline F4 abs(F4 a) { return _mm_andnot_ps(_mm_set1_ps(-0.f), a.v); }
inline bool any(F4 mask) { return _mm_movemask_ps(mask.v) != 0; }
#else
struct F4 {
    float v[4];
    explicit F4(float x) : v{x, x, x, x} {}
    F4() : v{} {}
    static F4 load(const float* p) { F4 r; std::copy(p, p + 4, r.v); return r; }
    void store(float* p) const { std::copy(v, v + 4, p); }
    template <class Op> static F4 map(F4 a, F4 b, Op op) { F4 r; for (int i = 0; i < 4; ++i) r.v[i] = op(a.v[i], b.v[i]); return r; }
};
inline float mask(bool b) { uint32_t bits = b ? ~0u : 0u; float f; std::memcpy(&f, &bits, 4); return f; }
inline uint32_t bits(float f) { uint32_t b; std::memcpy(&b, &f, 4); return b; }
inline F4 operator+(F4 a, F4 b) { return F4::map(a, b, [](float x, float y) { return x + y; }); }
inline F4 operator-(F4 a, F4 b) { return F4::map(a, b, [](float x, float y) { return x - y; }); }
inline F4 operator*(F4 a, F4 b) { return F4::map(a, b, [](float x, float y) { return x * y; }); }
inline F4 operator/(F4 a, F4 b) { return F4::map(a, b, [](float x, float y) { return x / y; }); }
inline F4 operator>(F4 a, F4 b) { return F4::map(a, b, [](float x, float y) { return mask(x > y); }); }
inline F4 operator>=(F4 a, F4 b) { return F4::map(a, b, [](float x, float y) { return mask(x >= y); }); }
inline F4 operator<=(F4 a, F4 b) { return F4::map(a, b, [](float x, float y) { return mask(x <= y); }); }
inline F4 operator&(F4 a, F4 b) { return F4::map(a, b, [](float x, float y) { return mask(bits(x) & bits(y)); }); }
inline F4 operator|(F4 a, F4 b) { return F4::map(a, b, [](float x, float y) { return mask(bits(x) | bits(y)); }); }
inline F4 operator!(F4 a) { return F4::map(a, a, [](float x, float) { return mask(!bits(x)); }); }
inline F4 select(F4 m, F4 a, F4 b) { F4 r; for (int i = 0; i < 4; ++i) r.v[i] = bits(m.v[i]) ? a.v[i] : b.v[i]; return r; }
inline F4 sqrt(F4 a) { return F4::map(a, a, [](float x, float) { return std::sqrt(x); }); }
inline F4 max(F4 a, F4 b) { return F4::map(a, b, [](float x, float y) { return std::max(x, y); }); }
inline F4 abs(F4 a) { return F4::map(a, a, [](float x, float) { return std::fabs(x); }); }
inline bool any(F4 m) { return bits(m.v[0]) | bits(m.v[1]) | bits(m.v[2]) | bits(m.v[3]); }
#endif


double safe_acos(double x) { return std::acos(std::clamp(x, -1.0, 1.0)); }

// v rotated around the unit axis k by the angle of cosine c and sine s (Rodrigues).
Vec3 rotate(Vec3 v, Vec3 k, double c, double s) {
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
    axis_settled = false;  // a float normalization, normalized again, may move by an ulp
}

void LightBounds::set_axis_up() {
    w[0] = w[1] = 0;
    w[2] = 1;
    axis_settled = true;
}

void LightBounds::settle_axis() {
    if (axis_settled) return;
    const float before[3] = {w[0], w[1], w[2]};
    set_axis(axis());
    axis_settled = w[0] == before[0] && w[1] == before[1] && w[2] == before[2];
}

LightBounds4::LightBounds4() {
    for (int i = 0; i < 4; ++i) {
        cx[i] = cy[i] = cz[i] = hx[i] = hy[i] = hz[i] = 0;
        wx[i] = wy[i] = 0;
        wz[i] = 1;
        phi[i] = 0;
        cos_theta_o[i] = 1;
    }
}

void LightBounds4::set(int lane, const LightBounds& b) {
    cx[lane] = 0.5f * (b.lo[0] + b.hi[0]);
    cy[lane] = 0.5f * (b.lo[1] + b.hi[1]);
    cz[lane] = 0.5f * (b.lo[2] + b.hi[2]);
    hx[lane] = 0.5f * (b.hi[0] - b.lo[0]);
    hy[lane] = 0.5f * (b.hi[1] - b.lo[1]);
    hz[lane] = 0.5f * (b.hi[2] - b.lo[2]);
    wx[lane] = b.w[0];
    wy[lane] = b.w[1];
    wz[lane] = b.w[2];
    phi[lane] = std::max(0.f, b.phi);
    // Two-sided or wider than a hemisphere: any direction (conservative). Narrower: the
    // hemisphere (conservative too).
    cos_theta_o[lane] = b.two_sided || b.cos_theta_e < 0 ? -1 : b.cos_theta_o;
}

void LightBounds4::importance(const LightQuery& q, float most[4], float least[4]) const {
    // Four lanes at once, branch-free: a lane that cannot light p ends with zero.
    const F4 px(q.p[0]), py(q.p[1]), pz(q.p[2]), nx(q.n[0]), ny(q.n[1]), nz(q.n[2]);
    const F4 zero(0.f), one(1.f);
    const F4 hx4 = F4::load(hx), hy4 = F4::load(hy), hz4 = F4::load(hz);
    const F4 wx4 = F4::load(wx), wy4 = F4::load(wy), wz4 = F4::load(wz);
    const F4 cos_o = F4::load(cos_theta_o);
    const F4 tx = px - F4::load(cx), ty = py - F4::load(cy), tz = pz - F4::load(cz);  // towards p
    const F4 dist2 = tx * tx + ty * ty + tz * tz;
    // The cosines below are dot products with t over |t|, their sines sqrt(|t|^2 - dot^2) over
    // |t|: every square root depends on the inputs alone, so they run side by side rather than
    // one after another.
    const F4 tw = wx4 * tx + wy4 * ty + wz4 * tz;  // |t| cos theta_w
    const F4 dist = sqrt(dist2);
    const F4 inv_dist = select(dist > zero, one / dist, zero);
    // The sphere around the box, rounded outwards (it must hold the box), and the cone of
    // directions from p that it subtends (all of them from inside).
    const F4 radius2 = (hx4 * hx4 + hy4 * hy4 + hz4 * hz4) * F4(1 + 1e-5f);
    const F4 radius = sqrt(radius2);
    const F4 inside = dist2 <= radius2;
    const F4 sin_b = select(inside, zero, radius * inv_dist);
    const F4 cos_b = select(inside, F4(-1.f), sqrt(max(zero, dist2 - radius2)) * inv_dist);
    // The box itself, tighter than its sphere up close (a wall's own windows from a point on the
    // wall): wholly behind emitters that all face w, or wholly below the horizon of n, it sends p
    // nothing. The extremes of a linear function over a box are centre +- half extents.
    F4 dark = (cos_o >= one) & (tw + hx4 * abs(wx4) + hy4 * abs(wy4) + hz4 * abs(wz4) <= zero);
    const F4 tn = zero - (tx * nx + ty * ny + tz * nz);  // |t| cos theta_i (n towards the light)
    if (q.has_normal) dark = dark | (hx4 * abs(nx) + hy4 * abs(ny) + hz4 * abs(nz) + tn <= zero);
    // theta_x = max(0, theta_w - theta_o), then cos(max(0, theta_x - theta_b)); normals pointing
    // everywhere (cos theta_o = -1: any cluster holding a lamp's globe) have no bound, and a
    // node of such clusters only (all of the lamps' tree) skips the cone.
    F4 cos_p = one;
    if (any(cos_o > F4(-1.f))) {
        const F4 cos_w = tw * inv_dist;
        const F4 sin_w = sqrt(max(zero, dist2 - tw * tw)) * inv_dist;
        const F4 within_o = cos_w > cos_o;
        const F4 sin_o = sqrt(max(zero, one - cos_o * cos_o));
        const F4 cos_x = select(within_o, one, cos_w * cos_o + sin_w * sin_o);
        const F4 sin_x = select(within_o, zero, sin_w * cos_o - cos_w * sin_o);
        cos_p = select((cos_o <= F4(-1.f)) | (cos_x > cos_b), one, cos_x * cos_b + sin_x * sin_b);
    }
    F4 factor = F4::load(phi) * cos_p;  // theta_e = 90 degrees: cos_p <= 0 sends nothing
    if (q.has_normal) {
        // Our surfaces only reflect (glass is never sampled): a cluster wholly below the
        // horizon of n cannot light p.
        const F4 cos_i = tn * inv_dist;
        const F4 sin_i = sqrt(max(zero, dist2 - tn * tn)) * inv_dist;
        factor = factor * select(cos_i > cos_b, one, cos_i * cos_b + sin_i * sin_b);
    }
    factor = select(dark | !(factor > zero), zero, factor);
    // Nearest point of the box (no nearer than kNearest) and farthest point of the sphere, each
    // distance with the visibility prior (kReach).
    const F4 ex = max(abs(tx) - hx4, zero), ey = max(abs(ty) - hy4, zero), ez = max(abs(tz) - hz4, zero);
    const F4 near2 = max(ex * ex + ey * ey + ez * ez, F4(kNearest * kNearest));
    const F4 far = dist + radius;
    const F4 far2 = max(far * far, near2);
    const F4 reach2(kReach * kReach);
    (factor / near2 * (reach2 / (reach2 + near2))).store(most);
    (factor / far2 * (reach2 / (reach2 + far2))).store(least);
}

void LightBounds::join(const LightBounds& b) {
    if (phi <= 0) {
        *this = b;
        return;
    }
    if (b.phi <= 0) return;
    for (int i = 0; i < 3; ++i) {
        lo[i] = std::min(lo[i], b.lo[i]);
        hi[i] = std::max(hi[i], b.hi[i]);
    }
    phi = phi + b.phi;
    cos_theta_e = std::min(cos_theta_e, b.cos_theta_e);
    two_sided = two_sided || b.two_sided;
    // Join the normal cones (the common cases first: a whole sphere such as a lamp's globe, or
    // two parallel walls).
    if (cos_theta_o <= -1 || b.cos_theta_o <= -1) {
        set_axis_up();
        cos_theta_o = -1;
        return;
    }
    if (w[0] == b.w[0] && w[1] == b.w[1] && w[2] == b.w[2]) {
        axis_settled = axis_settled || b.axis_settled;
        settle_axis();
        cos_theta_o = std::min(cos_theta_o, b.cos_theta_o);
        return;
    }
    // A single direction (a pane's) within the other cone, the usual case while a cluster
    // gathers panes: the branches below without an angle (acos is decreasing, so these are
    // exactly their tests).
    const Vec3 a_axis = axis();
    const float a_cos = cos_theta_o;
    const double cos_d = dot(a_axis, b.axis());
    if (b.cos_theta_o >= 1 && cos_d >= a_cos) {
        settle_axis();
        return;
    }
    if (a_cos >= 1 && cos_d >= b.cos_theta_o) {
        set_axis(b.axis());
        cos_theta_o = b.cos_theta_o;
        return;
    }
    // A single direction is the common cone: acos(1) is exactly 0, without the call.
    auto theta = [](float cos_theta) { return cos_theta >= 1 ? 0.0 : safe_acos(cos_theta); };
    const double theta_a = theta(a_cos), theta_b = theta(b.cos_theta_o);
    const double theta_d = safe_acos(cos_d);
    if (std::min(theta_d + theta_b, kPi) <= theta_a) {
        settle_axis();
    } else if (std::min(theta_d + theta_a, kPi) <= theta_b) {
        set_axis(b.axis());
        cos_theta_o = b.cos_theta_o;
    } else {
        const double theta_o = (theta_a + theta_d + theta_b) / 2;
        const Vec3 wr = cross(a_axis, b.axis());
        if (theta_o >= kPi || dot(wr, wr) == 0) {
            set_axis_up();
            cos_theta_o = -1;
        } else {
            // Rotated by theta_o - theta_a: by theta_o itself, and its cosine shared, when a is a
            // single direction (the usual case while panes gather).
            const double turn = theta_o - theta_a, cos_turn = std::cos(turn);
            const double cos_o = theta_a == 0 ? cos_turn : std::cos(theta_o);
            set_axis(rotate(a_axis, normalize(wr), cos_turn, std::sin(turn)));
            cos_theta_o = static_cast<float>(std::max(-1.0, cos_o - 1e-5));  // float rounding: never narrower
        }
    }
}

LightBounds union_of(const LightBounds& a, const LightBounds& b) {
    LightBounds u = a;
    u.join(b);
    return u;
}

}  // namespace citygen
