// Footprint geometry done by CGAL on exact predicates (exact constructions where new points
// are made): orientation, splitting a self-intersecting ring, simplification that keeps
// rings from crossing, and the exact overlap area. osmparse/polygons/cgal_footprint.cpp is the one
// translation unit of the footprint code that includes CGAL; callers see plain rings.
#pragma once

#include <vector>

#include "common/geometry.h"

namespace citygen {

// +1 for a counter-clockwise ring, -1 for a clockwise one, 0 for a degenerate one
// (CGAL::orientation_2: the exact sign of the turn at the extreme vertex; the ring must be simple).
int ring_orientation_exact(const Ring& ring);

// The inside (even-odd rule) of a self-intersecting or self-touching ring, as closed loops:
// the ring's segments go into a CGAL arrangement (intersection points constructed exactly),
// and for every face inside the ring the loops of its outer boundary and of its holes come
// out, cut at vertices they pass twice (pinches, and spikes that fold back over themselves).
// Points are rounded to float at the end, so the caller cleans and checks each loop.
std::vector<Ring> split_at_crossings_exact(const Ring& ring);

// Merges runs of nearly collinear edges of all `rings` at once (the outer rings and holes of
// one polygon) with CGAL's Polyline_simplification_2 on a constrained triangulation: vertices
// are only removed, never moved, and a removal that would make a ring cross itself or another
// ring is refused. A vertex goes when every original edge the new edge replaces points within
// max_angle_deg of it. Each ring keeps its sharpest corner. Returns the rings in input order;
// the input rings unchanged if they cross (the triangulation would add their crossing points).
std::vector<Ring> simplify_keeping_topology(const std::vector<Ring>& rings, double max_angle_deg);

// Area of a simple polygon `piece` inside (outer minus holes), by CGAL's Boolean set
// operations on exact constructions (the reference overlap_area is checked against).
double overlap_area_exact(const Ring& piece, const Ring& outer, const std::vector<Ring>& holes);

// CGAL's own check of a polygon with holes (CGAL::is_valid_polygon_with_holes): simple
// rings, outer counter-clockwise, holes clockwise, inside the outer, no crossings. clean_footprint
// checks its output with it.
bool polygon_is_valid_exact(const Ring& outer, const std::vector<Ring>& holes);

}  // namespace citygen
