#include "render/geometry/face_plane.h"

#include <cmath>

namespace citygen {

bool face_plane(const std::vector<Vec3>& points, FacePlane* plane) {
    if (points.size() < 3) return false;
    const Vec3 n = newell_normal(points);
    if (!(length(n) > 0)) return false;
    plane->normal = normalize(n);
    const Vec3 m{std::fabs(plane->normal.x), std::fabs(plane->normal.y), std::fabs(plane->normal.z)};
    plane->drop = m.z >= m.x && m.z >= m.y ? 2 : (m.y >= m.x ? 1 : 0);
    plane->axis_u = plane->drop == 0 ? 1 : 0;
    plane->axis_v = plane->drop == 2 ? 1 : 2;
    plane->offset = 0;
    for (Vec3 p : points) plane->offset += dot(plane->normal, p);
    plane->offset /= static_cast<double>(points.size());
    return true;
}

}  // namespace citygen
