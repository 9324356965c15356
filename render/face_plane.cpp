#include "face_plane.h"

#include <cmath>

namespace citygen {

bool face_plane(const std::vector<Vec3>& points, FacePlane* plane) {
    if (points.size() < 3) return false;
    // Newell's normal: robust for any planar polygon, its sign gives the front (CCW) side.
    Vec3 n{0, 0, 0};
    for (size_t i = 0; i < points.size(); ++i) {
        const Vec3 a = points[i] - points[0], b = points[(i + 1) % points.size()] - points[0];
        n = n + Vec3{(a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y)};
    }
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
