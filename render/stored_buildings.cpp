#include <algorithm>

#include "materials.h"
#include "stored_geometry.h"
#include "triangulate_polygon.h"

namespace citygen {

namespace {

// A quad per ring edge. Building material lies left of every edge (outer rings CCW, holes CW),
// so the counter-clockwise front of each wall faces right, away from the building.
void add_walls(const Ring& ring, double bottom, double top, uint32_t object, TriangleMesh& mesh) {
    for (size_t i = 0, n = ring.size(); i < n; ++i) {
        const Vec2 a = ring[i], b = ring[(i + 1) % n];
        if (a == b) continue;
        mesh.add_quad({a.x, a.y, bottom}, {b.x, b.y, bottom}, {b.x, b.y, top}, {a.x, a.y, top}, object,
                      kFacade);
    }
}

Ring oriented(const Ring& ring, bool counter_clockwise) {
    Ring r = ring;
    if ((signed_area(r) > 0) != counter_clockwise) std::reverse(r.begin(), r.end());
    return r;
}

}  // namespace

TriangleMesh build_stored_buildings(const Scene& scene) {
    TriangleMesh mesh;
    mesh.kind = ObjectKind::Building;
    const double ground = scene.ground.z;
    for (uint32_t index = 0; index < scene.buildings.size(); ++index) {
        const Building& b = scene.buildings[index];
        if (b.outer.size() < 3 || !(b.height > b.min_height)) continue;
        const double bottom = ground + b.min_height, top = ground + b.height;
        const Ring outer = oriented(b.outer, true);
        std::vector<Ring> holes;
        for (const Ring& h : b.holes) holes.push_back(oriented(h, false));

        add_walls(outer, bottom, top, index, mesh);
        for (const Ring& h : holes) add_walls(h, bottom, top, index, mesh);

        const PolygonTriangulation roof = triangulate_polygon(outer, holes);
        const uint32_t first_top = static_cast<uint32_t>(mesh.vertex_count());
        for (Vec2 p : roof.points) mesh.add_vertex({p.x, p.y, top});
        for (const auto& t : roof.triangles)
            mesh.add_triangle(first_top + t[0], first_top + t[1], first_top + t[2], index, kRoof);
        if (b.min_height > 0) {  // a floating part (bridge, overhang) needs an underside
            const uint32_t first_bottom = static_cast<uint32_t>(mesh.vertex_count());
            for (Vec2 p : roof.points) mesh.add_vertex({p.x, p.y, bottom});
            for (const auto& t : roof.triangles)
                mesh.add_triangle(first_bottom + t[0], first_bottom + t[2], first_bottom + t[1], index,
                                  kFacade);
        }
    }
    return mesh;
}

}  // namespace citygen
