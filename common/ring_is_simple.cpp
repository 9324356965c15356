// ring_is_simple with CGAL's sweep (is_simple_2, O(n log n)): a pairwise test took 48 s on a
// 100k-point outline. The one translation unit of common/ that includes CGAL.
#include "geometry.h"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>

namespace citygen {

bool ring_is_simple(const Ring& ring) {
    using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
    if (ring.size() < 3) return false;
    std::vector<Kernel::Point_2> points;
    points.reserve(ring.size());
    for (Vec2 p : ring) points.emplace_back(p.x, p.y);
    // Exact predicates: repeated points, touching or overlapping edges (also adjacent edges
    // folding back over each other) make a ring not simple.
    return CGAL::is_simple_2(points.begin(), points.end(), Kernel());
}

}  // namespace citygen
