// The geometric decisions of footprint cleaning, answered exactly for the double coordinates
// given. Each is a float evaluation with an error bound (a static filter in Shewchuk's style:
// Adaptive Precision Floating-Point Arithmetic and Fast Robust Geometric Predicates, 1997) that
// answers when the rounding error cannot change the sign, and falls back to CGAL's exact
// arithmetic otherwise (osmparse/polygons/ring_is_simple.cpp). One definition of each: ring
// simplicity, hole containment, the 1 cm clean-up and the overlap code all use these.
#pragma once

#include <cmath>
#include <limits>

#include "common/geometry.h"

namespace citygen {

namespace exact_detail {
constexpr double kEpsilon = std::numeric_limits<double>::epsilon() / 2;  // 2^-53, a rounding's relative error
// Shewchuk's ccwerrboundA: |computed - true| of the orientation determinant is below this
// times |left product| + |right product|.
constexpr double kOrientationError = (3 + 16 * kEpsilon) * kEpsilon;
// Generous relative error of a sum of two squares, a square root and a product of those
// (each rounding adds at most kEpsilon; 16 covers the chain with room).
constexpr double kDistanceError = 16 * kEpsilon;

// The CGAL fallbacks, when the float evaluation cannot tell.
int orientation_by_cgal(Vec2 a, Vec2 b, Vec2 c);
bool within_distance_by_cgal(Vec2 p, Vec2 q, double distance);
bool near_line_by_cgal(Vec2 p, Vec2 a, Vec2 b, double distance);
}  // namespace exact_detail

// The sign of cross(b - a, c - a): +1 when a, b, c turn counter-clockwise, -1 clockwise, 0 collinear.
inline int exact_orientation(Vec2 a, Vec2 b, Vec2 c) {
    const double left = (b.x - a.x) * (c.y - a.y), right = (b.y - a.y) * (c.x - a.x);
    const double det = left - right;
    // The products zero or of opposite signs: det has their sign, and theirs are exact (a rounded
    // difference of doubles is zero only when they are equal).
    auto sign = [](double v) { return (v > 0) - (v < 0); };
    double magnitude;
    if (left > 0) {
        if (right <= 0) return sign(det);
        magnitude = left + right;
    } else if (left < 0) {
        if (right >= 0) return sign(det);
        magnitude = -left - right;
    } else {
        return sign(det);
    }
    const double bound = exact_detail::kOrientationError * magnitude;
    if (det > bound) return 1;
    if (-det > bound) return -1;
    return exact_detail::orientation_by_cgal(a, b, c);
}

// True when segments [a, b] and [c, d] share any point (touching and overlapping count).
inline bool exact_segments_touch(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
    // Within the segment's box: comparisons of doubles are exact.
    auto in_box = [](Vec2 s, Vec2 e, Vec2 p) {
        return std::min(s.x, e.x) <= p.x && p.x <= std::max(s.x, e.x) && std::min(s.y, e.y) <= p.y &&
               p.y <= std::max(s.y, e.y);
    };
    const int o1 = exact_orientation(a, b, c), o2 = exact_orientation(a, b, d);
    const int o3 = exact_orientation(c, d, a), o4 = exact_orientation(c, d, b);
    if (o1 != o2 && o3 != o4) return true;
    return (o1 == 0 && in_box(a, b, c)) || (o2 == 0 && in_box(a, b, d)) || (o3 == 0 && in_box(c, d, a)) ||
           (o4 == 0 && in_box(c, d, b));
}

// What edge a -> b adds to p's winding number, with an exact turn: nothing unless a.y <= p.y < b.y
// or b.y <= p.y < a.y.
inline int exact_winding_step(Vec2 a, Vec2 b, Vec2 p) {
    if (a.y <= p.y) return b.y > p.y && exact_orientation(a, b, p) > 0 ? 1 : 0;
    return b.y <= p.y && exact_orientation(a, b, p) < 0 ? -1 : 0;
}
// Winding-number point in ring with exact turns: exact for a point off the boundary; a point on
// it may go either way (callers test the boundaries apart first).
inline bool exact_point_in_ring(Vec2 p, const Vec2* ring, size_t n) {
    int winding = 0;
    for (size_t i = 0; i < n; ++i) winding += exact_winding_step(ring[i], ring[i + 1 == n ? 0 : i + 1], p);
    return winding != 0;
}
inline bool exact_point_in_ring(Vec2 p, const Ring& ring) { return exact_point_in_ring(p, ring.data(), ring.size()); }

// True when |p - q| <= distance.
inline bool exact_within_distance(Vec2 p, Vec2 q, double distance) {
    const double dx = p.x - q.x, dy = p.y - q.y;
    const double d2 = dx * dx + dy * dy, limit = distance * distance;
    if (d2 < limit * (1 - exact_detail::kDistanceError)) return true;
    if (d2 > limit * (1 + exact_detail::kDistanceError)) return false;
    return exact_detail::within_distance_by_cgal(p, q, distance);
}

// True when p is within `distance` of the line through a and b (of a itself when a == b): the
// test that drops a collinear vertex or a spike.
inline bool exact_near_line(Vec2 p, Vec2 a, Vec2 b, double distance) {
    if (a == b) return exact_within_distance(p, a, distance);
    const double left = (b.x - a.x) * (p.y - a.y), right = (b.y - a.y) * (p.x - a.x);
    const double cross_error = exact_detail::kOrientationError * (std::fabs(left) + std::fabs(right));
    const double offset = std::fabs(left - right);  // |cross|, the distance times |b - a|
    const double dx = b.x - a.x, dy = b.y - a.y;
    const double reach = distance * std::sqrt(dx * dx + dy * dy);  // the limit on |cross|
    if (offset + cross_error < reach * (1 - exact_detail::kDistanceError)) return true;
    if (offset - cross_error > reach * (1 + exact_detail::kDistanceError)) return false;
    return exact_detail::near_line_by_cgal(p, a, b, distance);
}

// True when the turn a -> b -> c folds straight back (b - a and c - b collinear and opposed):
// the two edges then overlap along a stretch.
inline bool exact_folds_back(Vec2 a, Vec2 b, Vec2 c) {
    if (exact_orientation(a, b, c) != 0) return false;
    // Collinear: each axis's product (b - a)(c - b) has the sign of the dot product or is zero,
    // and the sign of a product of rounded differences is exact.
    auto sign = [](double v) { return (v > 0) - (v < 0); };
    return sign(b.x - a.x) * sign(c.x - b.x) < 0 || sign(b.y - a.y) * sign(c.y - b.y) < 0;
}

}  // namespace citygen
