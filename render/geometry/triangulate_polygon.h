// Triangulation of a polygon with holes (constrained Delaunay, CGAL), for roofs and any
// non-convex flat polygon.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "common/geometry.h"

namespace citygen {

struct PolygonTriangulation {
    std::vector<Vec2> points;                      // may include points where edges crossed
    std::vector<std::array<uint32_t, 3>> triangles;  // counter-clockwise
};

// Triangles covering the inside of `outer` minus the `holes` (orientation of the rings does
// not matter; inside is decided by nesting). Convex rings without holes are fanned directly.
PolygonTriangulation triangulate_polygon(const Ring& outer, const std::vector<Ring>& holes = {});

}  // namespace citygen
