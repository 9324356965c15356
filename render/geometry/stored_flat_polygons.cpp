#include <algorithm>

#include "render/geometry/stored_geometry.h"
#include "render/geometry/triangulate_polygon.h"
#include "render/materials/materials.h"

namespace citygen {

void add_flat_polygon(const Ring& ring, double z, uint32_t object, uint16_t material, TriangleMesh& mesh) {
    const PolygonTriangulation tri = triangulate_polygon(ring);
    const uint32_t first = static_cast<uint32_t>(mesh.vertex_count());
    for (Vec2 p : tri.points) mesh.add_vertex({p.x, p.y, z});
    for (const auto& t : tri.triangles) mesh.add_triangle(first + t[0], first + t[1], first + t[2], object, material);
}

TriangleMesh build_stored_roads(const Scene& scene) {
    TriangleMesh mesh;
    mesh.kind = ObjectKind::Road;
    const double z = scene.ground.z + kRoadLift;
    for (uint32_t i = 0; i < scene.roads.size(); ++i) add_flat_polygon(scene.roads[i].quad, z, i, kAsphalt, mesh);
    return mesh;
}

TriangleMesh build_stored_joints(const Scene& scene) {
    TriangleMesh mesh;
    mesh.kind = ObjectKind::Joint;
    const double z = scene.ground.z + kRoadLift;
    for (uint32_t i = 0; i < scene.joints.size(); ++i)
        add_flat_polygon(scene.joints[i].polygon, z, i, kAsphalt, mesh);
    return mesh;
}

bool sidewalk_shape(const Scene& scene, uint32_t index, SidewalkShape* shape) {
    const Sidewalk& s = scene.sidewalks[index];
    if (s.polygon.size() < 3) return false;
    shape->ring = s.polygon;
    if (signed_area(shape->ring) < 0) std::reverse(shape->ring.begin(), shape->ring.end());
    shape->road_z = scene.ground.z + kRoadLift;
    shape->top_z = shape->road_z + std::max(0.0, s.curb_height);
    return true;
}

TriangleMesh build_stored_sidewalks(const Scene& scene) {
    TriangleMesh mesh;
    mesh.kind = ObjectKind::Sidewalk;
    SidewalkShape shape;
    for (uint32_t i = 0; i < scene.sidewalks.size(); ++i) {
        if (!sidewalk_shape(scene, i, &shape)) continue;
        add_flat_polygon(shape.ring, shape.top_z, i, kSidewalk, mesh);
        if (!shape.has_curb()) continue;
        // Curb faces on every edge, facing out of the (counter-clockwise) polygon.
        const Ring& ring = shape.ring;
        const double road = shape.road_z, top = shape.top_z;
        for (size_t k = 0, n = ring.size(); k < n; ++k) {
            const Vec2 a = ring[k], b = ring[(k + 1) % n];
            if (a == b) continue;
            mesh.add_quad({a.x, a.y, road}, {b.x, b.y, road}, {b.x, b.y, top}, {a.x, a.y, top}, i, kCurb);
        }
    }
    return mesh;
}

Box2 terrain_extent(const Scene& scene) {
    Box2 box;
    if (scene.ground.min.x < scene.ground.max.x && scene.ground.min.y < scene.ground.max.y) {
        box.extend(scene.ground.min);
        box.extend(scene.ground.max);
    } else {
        box.extend(scene.header.bounds_min);
        box.extend(scene.header.bounds_max);
    }
    for (const Building& b : scene.buildings)
        for (Vec2 p : b.outer) box.extend(p);
    // Far enough that the plane's edge sits on the horizon from any sensible camera (a plane at
    // z = const stays exact in float even this large).
    const double margin = 1e6;
    box.extend(box.min - Vec2{margin, margin});
    box.extend(box.max + Vec2{margin, margin});
    return box;
}

TriangleMesh build_stored_terrain(const Scene& scene) {
    TriangleMesh mesh;
    mesh.kind = ObjectKind::Terrain;
    const Box2 e = terrain_extent(scene);
    const double z = scene.ground.z;
    mesh.add_quad({e.min.x, e.min.y, z}, {e.max.x, e.min.y, z}, {e.max.x, e.max.y, z}, {e.min.x, e.max.y, z}, 0,
                  kGround);
    return mesh;
}

}  // namespace citygen
