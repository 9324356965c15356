// ring_is_simple: a pairwise test for small rings, CGAL's sweep (is_simple_2, O(n log n)) for
// the rest: the pairwise test is quadratic, far too slow on an outline of many thousand points.
// Both are exact and give the same answer (tests/osmparse/polygons/ring_is_simple_test.cpp
// compares them). The pairwise test stays for small rings for speed: building the sweep costs
// more there (tests/bench/footprint_bench; docs/bench/2026-11-buildings.md).
// This file is also where exact_predicates.h falls back to CGAL (one translation unit with its headers).
#include "osmparse/polygons/ring_is_simple.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Exact_rational.h>
#include <CGAL/Polygon_2_algorithms.h>

#include "osmparse/polygons/exact_predicates.h"

namespace citygen {

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

namespace exact_detail {

int orientation_by_cgal(Vec2 a, Vec2 b, Vec2 c) {
    return static_cast<int>(CGAL::orientation(Kernel::Point_2(a.x, a.y), Kernel::Point_2(b.x, b.y), Kernel::Point_2(c.x, c.y)));
}

// Rationals hold every double, their differences, products and sums exactly.
using Rational = CGAL::Exact_rational;

bool within_distance_by_cgal(Vec2 p, Vec2 q, double distance) {
    const Rational dx = Rational(p.x) - Rational(q.x), dy = Rational(p.y) - Rational(q.y);
    return dx * dx + dy * dy <= Rational(distance) * Rational(distance);
}

bool near_line_by_cgal(Vec2 p, Vec2 a, Vec2 b, double distance) {
    const Rational dx = Rational(b.x) - Rational(a.x), dy = Rational(b.y) - Rational(a.y);
    const Rational cross = dx * (Rational(p.y) - Rational(a.y)) - dy * (Rational(p.x) - Rational(a.x));
    // distance to the line = |cross| / |b - a|: compare the squares.
    return cross * cross <= Rational(distance) * Rational(distance) * (dx * dx + dy * dy);
}

}  // namespace exact_detail

namespace {

// Below this many points the pairwise test is faster than building the sweep.
constexpr size_t kPairwiseMaxPoints = 32;

bool ring_is_simple_pairwise(const Ring& ring) {
    const size_t n = ring.size();
    for (size_t i = 0; i < n; ++i) {
        // Adjacent edges folding back over each other overlap along a stretch.
        const Vec2 a = ring[(i + n - 1) % n], b = ring[i], c = ring[(i + 1) % n];
        if (exact_folds_back(a, b, c)) return false;
        for (size_t j = i + 1; j < n; ++j) {
            if (ring[i] == ring[j]) return false;
            // Adjacent edges share a vertex by construction; skip them.
            if (j == i + 1 || (i == 0 && j == n - 1)) continue;
            if (exact_segments_touch(ring[i], ring[(i + 1) % n], ring[j], ring[(j + 1) % n])) return false;
        }
    }
    return true;
}

}  // namespace

bool ring_is_simple_sweep(const Ring& ring) {
    if (ring.size() < 3) return false;
    std::vector<Kernel::Point_2> points;
    points.reserve(ring.size());
    for (Vec2 p : ring) points.emplace_back(p.x, p.y);
    return CGAL::is_simple_2(points.begin(), points.end(), Kernel());
}

bool ring_is_simple(const Ring& ring) {
    if (ring.size() < 3) return false;
    return ring.size() <= kPairwiseMaxPoints ? ring_is_simple_pairwise(ring) : ring_is_simple_sweep(ring);
}

}  // namespace citygen
