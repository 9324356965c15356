// The plane of a planar polygon in 3D (roof faces, gable walls), the one rule both geometry
// modes share: the stored mode triangulates the face in this projection and puts the points
// back on this plane, the procedural mode intersects this plane and tests the hit point in the
// same projection.
#pragma once

#include <vector>

#include "common/geometry.h"

namespace citygen {

struct FacePlane {
    Vec3 normal;      // unit Newell normal: the front is the side the points run counter-clockwise
    double offset = 0;  // dot(normal, p) = offset, through the mean of the points
    // The normal's dominant axis is dropped; the face is projected on the other two.
    int drop = 2, axis_u = 0, axis_v = 1;
};

// False for fewer than 3 points or a face without area.
bool face_plane(const std::vector<Vec3>& points, FacePlane* plane);

}  // namespace citygen
