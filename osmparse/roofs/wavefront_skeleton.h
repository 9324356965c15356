// The interior straight skeleton of a simple footprint without holes by direct wavefront
// propagation (double precision), for the bent footprints of hipped roofs: on a small footprint
// CGAL's exact predicates cost far more (docs/bench/2026-11-buildings.md).
#pragma once

#include <vector>

#include "common/geometry.h"
#include "osmparse/roofs/roof_skeleton.h"

namespace citygen {

// The faces of the straight skeleton of `outer` (counter-clockwise, no repeated closing point),
// in the form and order straight_skeleton_faces() gives them (one face per footprint edge,
// starting at that edge's end point). False, with `faces` empty, whenever the answer could
// depend on rounding: parallel neighbouring edges, two events at (nearly) the same time, a
// reflex vertex running into a wavefront vertex, nodes a face cannot order. The caller then
// asks CGAL, whose exact predicates decide those cases.
bool wavefront_skeleton_faces(const Ring& outer, std::vector<SkeletonFace>* faces);

}  // namespace citygen
