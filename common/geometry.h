// Small 2D/3D vector types and the polygon predicates every stage shares.
#pragma once

#include <algorithm>
#include <cmath>
#include <vector>

namespace citygen {

constexpr double kPi = 3.14159265358979323846;  // the one definition (C++17 has no std::numbers)

struct Vec2 {
    double x = 0, y = 0;
    Vec2() = default;
    Vec2(double x_, double y_) : x(x_), y(y_) {}
    Vec2 operator+(Vec2 o) const { return {x + o.x, y + o.y}; }
    Vec2 operator-(Vec2 o) const { return {x - o.x, y - o.y}; }
    Vec2 operator*(double s) const { return {x * s, y * s}; }
    bool operator==(const Vec2& o) const { return x == o.x && y == o.y; }
    bool operator!=(const Vec2& o) const { return !(*this == o); }
};

inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.y * b.y; }
inline double cross(Vec2 a, Vec2 b) { return a.x * b.y - a.y * b.x; }
inline double length(Vec2 a) { return std::sqrt(dot(a, a)); }
inline Vec2 normalize(Vec2 a) { double l = length(a); return l > 0 ? a * (1.0 / l) : a; }
inline Vec2 perp_left(Vec2 a) { return {-a.y, a.x}; }  // rotated 90 degrees CCW

struct Vec3 {
    double x = 0, y = 0, z = 0;
    Vec3() = default;
    Vec3(double x_, double y_, double z_) : x(x_), y(y_), z(z_) {}
    Vec3 operator+(Vec3 o) const { return {x + o.x, y + o.y, z + o.z}; }
    Vec3 operator-(Vec3 o) const { return {x - o.x, y - o.y, z - o.z}; }
    Vec3 operator*(double s) const { return {x * s, y * s, z * s}; }
    Vec3 operator*(Vec3 o) const { return {x * o.x, y * o.y, z * o.z}; }
    Vec3 operator-() const { return {-x, -y, -z}; }
    double operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
};

inline double dot(Vec3 a, Vec3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
inline Vec3 cross(Vec3 a, Vec3 b) {
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
inline double length(Vec3 a) { return std::sqrt(dot(a, a)); }
inline Vec3 normalize(Vec3 a) { double l = length(a); return l > 0 ? a * (1.0 / l) : a; }

// Newell's normal of a polygon in 3D, not normalised (zero when it has no area): robust for any
// planar polygon, and it points to the side from which the points run counter-clockwise.
inline Vec3 newell_normal(const std::vector<Vec3>& points) {
    Vec3 n{0, 0, 0};
    for (size_t i = 0; i < points.size(); ++i) {
        const Vec3 a = points[i] - points[0], b = points[(i + 1) % points.size()] - points[0];
        n = n + Vec3{(a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y)};
    }
    return n;
}

// A ring is a closed polygon boundary stored without repeating the first point.
using Ring = std::vector<Vec2>;

// Twice the signed area is avoided on purpose: callers want square metres.
// Positive for counter-clockwise rings.
inline double signed_area(const Ring& ring) {
    double a = 0;
    for (size_t i = 0, n = ring.size(); i < n; ++i) a += cross(ring[i], ring[(i + 1) % n]);
    return 0.5 * a;
}

// What edge a -> b adds to p's winding number: nothing unless a.y <= p.y < b.y or b.y <= p.y < a.y.
inline int winding_step(Vec2 a, Vec2 b, Vec2 p) {
    if (a.y <= p.y) return b.y > p.y && cross(b - a, p - a) > 0 ? 1 : 0;
    return b.y <= p.y && cross(b - a, p - a) < 0 ? -1 : 0;
}
// Winding-number point-in-polygon over n points stored back to back; points exactly on the
// boundary may go either way.
inline bool point_in_ring(Vec2 p, const Vec2* ring, size_t n) {
    int winding = 0;
    for (size_t i = 0; i < n; ++i) winding += winding_step(ring[i], ring[i + 1 == n ? 0 : i + 1], p);
    return winding != 0;
}
inline bool point_in_ring(Vec2 p, const Ring& ring) { return point_in_ring(p, ring.data(), ring.size()); }

// Distance from p to the nearest point on the ring's boundary.
inline double distance_to_boundary(Vec2 p, const Ring& ring) {
    double best = 1e300;
    for (size_t i = 0, n = ring.size(); i < n; ++i) {
        const Vec2 a = ring[i], b = ring[(i + 1) % n], ab = b - a;
        const double len2 = dot(ab, ab);
        const double t = len2 > 0 ? std::clamp(dot(p - a, ab) / len2, 0.0, 1.0) : 0.0;
        best = std::min(best, length(p - (a + ab * t)));
    }
    return best;
}

// True when segments [a,b] and [c,d] share any point.
bool segments_intersect(Vec2 a, Vec2 b, Vec2 c, Vec2 d);

// True for a convex ring (either orientation), allowing collinear vertices.
bool ring_is_convex(const Ring& ring);

struct Box2 {
    Vec2 min{1e300, 1e300}, max{-1e300, -1e300};
    // std::min(current, p): a NaN coordinate is ignored, as std::fmin would, but inlined (fmin
    // is a call into libm).
    void extend(Vec2 p) {
        min.x = std::min(min.x, p.x); min.y = std::min(min.y, p.y);
        max.x = std::max(max.x, p.x); max.y = std::max(max.y, p.y);
    }
    bool empty() const { return min.x > max.x; }
    bool overlaps(const Box2& o) const {
        return min.x <= o.max.x && o.min.x <= max.x && min.y <= o.max.y && o.min.y <= max.y;
    }
};

inline Box2 bounds_of(const Ring& ring) { Box2 b; for (Vec2 p : ring) b.extend(p); return b; }

}  // namespace citygen
