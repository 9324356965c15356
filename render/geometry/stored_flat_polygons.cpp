#include <algorithm>

#include "render/geometry/bridge_geometry.h"
#include "render/geometry/ground.h"
#include "render/geometry/stored_geometry.h"
#include "render/geometry/terrain_geometry.h"
#include "render/geometry/triangulate_polygon.h"
#include "render/materials/materials.h"

namespace citygen {

void add_flat_polygon(const Ring& ring, double z, uint32_t object, uint16_t material, TriangleMesh& mesh) {
    const PolygonTriangulation tri = triangulate_polygon(ring);
    const uint32_t first = static_cast<uint32_t>(mesh.vertex_count());
    for (Vec2 p : tri.points) mesh.add_vertex({p.x, p.y, z});
    for (const auto& t : tri.triangles) mesh.add_triangle(first + t[0], first + t[1], first + t[2], object, material);
}

void add_ground_polygon(const Scene& scene, const Ring& outer, const std::vector<Ring>& holes, double lift,
                        uint32_t object, uint16_t material, TriangleMesh& mesh) {
    if (scene.terrain.empty()) {
        const double z = scene.ground.z + lift;
        const PolygonTriangulation tri = triangulate_polygon(outer, holes);
        const uint32_t first = static_cast<uint32_t>(mesh.vertex_count());
        for (Vec2 p : tri.points) mesh.add_vertex({p.x, p.y, z});
        for (const auto& t : tri.triangles) mesh.add_triangle(first + t[0], first + t[1], first + t[2], object, material);
        return;
    }
    const DrapedPolygon draped = drape_polygon(scene, outer, holes, lift);
    const uint32_t first = static_cast<uint32_t>(mesh.vertex_count());
    for (const Vec3& p : draped.points) mesh.add_vertex(p);
    for (const auto& t : draped.triangles) mesh.add_triangle(first + t[0], first + t[1], first + t[2], object, material);
}

TriangleMesh build_stored_roads(const Scene& scene) {
    TriangleMesh mesh;
    mesh.kind = ObjectKind::Road;
    const std::vector<DeckLine> decks = drawn_decks(scene);
    for (uint32_t i = 0; i < scene.roads.size(); ++i) {
        if (i < decks.size() && decks[i].valid) {
            add_faces(deck_piece_faces(edge_deck(decks, i), scene.roads[i].quad, kRoadLift, kAsphalt), i, mesh);
            add_faces(deck_piers(scene, decks[i], scene.roads[i].width), i, mesh);
            continue;
        }
        add_ground_polygon(scene, scene.roads[i].quad, {}, kRoadLift, i, kAsphalt, mesh);
    }
    return mesh;
}

TriangleMesh build_stored_joints(const Scene& scene) {
    TriangleMesh mesh;
    mesh.kind = ObjectKind::Joint;
    const std::vector<DeckLine> decks = drawn_decks(scene);
    for (uint32_t i = 0; i < scene.joints.size(); ++i) {
        if (const DeckSurface deck = joint_deck(scene, decks, scene.joints[i]); deck.valid()) {
            add_faces(deck_piece_faces(deck, scene.joints[i].polygon, kRoadLift, kAsphalt), i, mesh);
            continue;
        }
        add_ground_polygon(scene, scene.joints[i].polygon, {}, kRoadLift, i, kAsphalt, mesh);
    }
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

std::vector<CurbFace> draped_curb_faces(const Scene& scene, const SidewalkShape& shape) {
    std::vector<CurbFace> faces;
    if (!shape.has_curb()) return faces;
    const double curb = shape.top_z - shape.road_z;
    const Ring ring = split_at_field_lines(scene, shape.ring);
    for (size_t k = 0, n = ring.size(); k < n; ++k) {
        const Vec2 a = ring[k], b = ring[(k + 1) % n];
        if (a == b) continue;
        const double za = ground_height(scene, a.x, a.y) + kRoadLift, zb = ground_height(scene, b.x, b.y) + kRoadLift;
        faces.push_back({Vec3{a.x, a.y, za}, Vec3{b.x, b.y, zb}, Vec3{b.x, b.y, zb + curb}, Vec3{a.x, a.y, za + curb}});
    }
    return faces;
}

namespace {

void add_draped_sidewalk(const Scene& scene, const SidewalkShape& shape, uint32_t index, TriangleMesh& mesh) {
    add_ground_polygon(scene, shape.ring, {}, kRoadLift + (shape.top_z - shape.road_z), index, kSidewalk, mesh);
    for (const CurbFace& f : draped_curb_faces(scene, shape)) mesh.add_quad(f[0], f[1], f[2], f[3], index, kCurb);
}

}  // namespace

TriangleMesh build_stored_sidewalks(const Scene& scene) {
    TriangleMesh mesh;
    mesh.kind = ObjectKind::Sidewalk;
    SidewalkShape shape;
    const std::vector<DeckLine> decks = drawn_decks(scene);
    for (uint32_t i = 0; i < scene.sidewalks.size(); ++i) {
        if (!sidewalk_shape(scene, i, &shape)) continue;
        if (const DeckSurface deck = sidewalk_deck(scene, decks, scene.sidewalks[i]); deck.valid()) {
            add_faces(deck_piece_faces(deck, shape.ring, kRoadLift + (shape.top_z - shape.road_z), kSidewalk), i, mesh);
            continue;
        }
        if (!scene.terrain.empty()) {
            add_draped_sidewalk(scene, shape, i, mesh);
            continue;
        }
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
    if (!scene.terrain.empty()) return build_stored_field_terrain(scene);
    TriangleMesh mesh;
    mesh.kind = ObjectKind::Terrain;
    const Box2 e = terrain_extent(scene);
    const double z = scene.ground.z;
    mesh.add_quad({e.min.x, e.min.y, z}, {e.max.x, e.min.y, z}, {e.max.x, e.max.y, z}, {e.min.x, e.max.y, z}, 0,
                  kGround);
    return mesh;
}

}  // namespace citygen
