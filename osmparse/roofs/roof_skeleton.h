// The interior straight skeleton of a footprint (CGAL), as the faces of a hipped roof, and the
// inward offset it gives (for blocks and lots).
#pragma once

#include <vector>

#include "common/geometry.h"

namespace citygen {

// One face of the skeleton: the polygon swept by one footprint edge as it moves inward, with
// the time (distance from that edge) at which each point was reached: 0 on the footprint.
struct SkeletonFace {
    std::vector<Vec2> points;  // counter-clockwise
    std::vector<double> times;
};

// Faces of the interior straight skeleton of `outer` (CCW) with `holes` (CW). False when CGAL
// cannot build it (degenerate input); `faces` is then left empty.
bool straight_skeleton_faces(const Ring& outer, const std::vector<Ring>& holes, std::vector<SkeletonFace>* faces);

// The polygons `distance` inside `outer` (CCW; several when it pinches apart, none when it
// vanishes), counter-clockwise. False when CGAL cannot build it.
bool inset_polygon(const Ring& outer, double distance, std::vector<Ring>* out);

}  // namespace citygen
