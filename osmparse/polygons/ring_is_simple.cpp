// ring_is_simple: a pairwise test for small rings, CGAL's sweep (is_simple_2, O(n log n)) for
// the rest; a pairwise test took 48 s on a 100k-point outline. Both give the same answer
// (tests/osmparse/polygons/ring_is_simple_test.cpp compares them). The pairwise test stays for small
// rings for speed: the sweep for every ring took 1.7-2.6x as long on Kaiserslautern's
// footprints (tests/bench/footprint_bench).
#include "osmparse/polygons/ring_is_simple.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>

namespace citygen {

namespace {

// Below this many points the pairwise test is faster than building the sweep.
constexpr size_t kPairwiseMaxPoints = 32;

bool ring_is_simple_pairwise(const Ring& ring) {
    const size_t n = ring.size();
    for (size_t i = 0; i < n; ++i) {
        // Adjacent edges folding back over each other overlap along a stretch.
        const Vec2 a = ring[(i + n - 1) % n], b = ring[i], c = ring[(i + 1) % n];
        if (cross(b - a, c - b) == 0 && dot(b - a, c - b) < 0) return false;
        for (size_t j = i + 1; j < n; ++j) {
            if (ring[i] == ring[j]) return false;
            // Adjacent edges share a vertex by construction; skip them.
            if (j == i + 1 || (i == 0 && j == n - 1)) continue;
            if (segments_intersect(ring[i], ring[(i + 1) % n], ring[j], ring[(j + 1) % n])) return false;
        }
    }
    return true;
}

}  // namespace

bool ring_is_simple_sweep(const Ring& ring) {
    using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
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
