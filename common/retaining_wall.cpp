#include "common/retaining_wall.h"

#include <algorithm>
#include <cmath>

#include "common/ground.h"

namespace citygen {

namespace {

// A segment's left normal (unit), or none for a point.
Vec2 left_normal(Vec2 a, Vec2 b) {
    const double l = length(b - a);
    return l > 0 ? perp_left((b - a) * (1 / l)) : Vec2{0, 0};
}

// The station at p: its faces at `offset` (half the thickness along the mitre, see below), its
// heights from the ground at both faces and a cell's diagonal out on the high side.
WallStation station(const Scene& scene, Vec2 p, Vec2 offset, Vec2 normal) {
    WallStation s;
    s.left = p + offset;
    s.right = p - offset;
    const Vec2 far = p + normal * (scene.terrain.cell * std::sqrt(2.0));
    const double left = ground_height(scene, s.left.x, s.left.y), right = ground_height(scene, s.right.x, s.right.y);
    s.top = std::max({left, right, ground_height(scene, far.x, far.y)}) + kRetainingWallParapet;
    s.bottom = std::min(left, right) - kRetainingWallFooting;
    return s;
}

}  // namespace

std::vector<WallStation> wall_stations(const Scene& scene, const RetainingWall& wall) {
    std::vector<WallStation> stations;
    if (scene.terrain.empty()) return stations;
    // The line without repeated points; a closed line's first and last are its one joint.
    std::vector<Vec2> line;
    for (Vec2 p : wall.line)
        if (line.empty() || p != line.back()) line.push_back(p);
    if (line.size() < 2) return stations;
    const bool closed = line.size() > 3 && line.front() == line.back();
    const size_t n = line.size();
    const double half = 0.5 * kRetainingWallThickness;
    for (size_t k = 0; k + 1 < n; ++k) {
        const Vec2 a = line[k], b = line[k + 1];
        const Vec2 normal = left_normal(a, b);
        // The mitre at a vertex: along the two segments' mean normal, long enough that each face
        // stays half the thickness from its segment (at most twice that at a sharp turn).
        const auto mitre = [&](size_t v, Vec2* offset, Vec2* unit) {
            const bool has_before = v > 0 || closed, has_after = v + 1 < n || closed;
            const Vec2 before = has_before ? left_normal(line[v > 0 ? v - 1 : n - 2], line[v]) : normal;
            const Vec2 after = has_after ? left_normal(line[v], line[v + 1 < n ? v + 1 : 1]) : normal;
            Vec2 m = before + after;
            const double l = length(m);
            m = l > 1e-9 ? m * (1 / l) : after;
            const double c = std::max(0.5, dot(m, after));
            *offset = m * (half / c);
            *unit = m;
        };
        Vec2 offset, unit;
        mitre(k, &offset, &unit);
        if (k == 0) stations.push_back(station(scene, a, offset, unit));
        // Where the line or its faces cross the field's lines: the ground along each is linear
        // between them. One parameter for all three: the faces run parallel to the segment.
        std::vector<double> ts = field_line_crossings(scene.terrain, a, b);
        for (const double side : {1.0, -1.0}) {
            const Vec2 d = normal * (side * half);
            const std::vector<double> more = field_line_crossings(scene.terrain, a + d, b + d);
            ts.insert(ts.end(), more.begin(), more.end());
        }
        std::sort(ts.begin(), ts.end());
        double last = 0;
        for (double t : ts) {
            if (t - last < 1e-6 || t > 1 - 1e-6) continue;
            last = t;
            stations.push_back(station(scene, a + (b - a) * t, normal * half, normal));
        }
        mitre(k + 1, &offset, &unit);
        stations.push_back(station(scene, b, offset, unit));
    }
    return stations;
}

}  // namespace citygen
