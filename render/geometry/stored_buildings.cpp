#include <algorithm>
#include <cmath>

#include "render/facade/facade_materials.h"
#include "render/facade/facade_mesh.h"
#include "render/geometry/face_plane.h"
#include "render/geometry/ground.h"
#include "render/geometry/stored_geometry.h"
#include "render/geometry/triangulate_polygon.h"
#include "render/materials/materials.h"

namespace citygen {

namespace {

// The walls with their facades (render/facade/facade.h): every window, balcony and shop front as
// triangles. Wall i is the same wall the procedural mode intersects (building_wall), with the
// building on its left, so each surface's front faces the side it is seen from.
void add_facade_walls(const Building& b, uint32_t object, double bottom, const FacadeOptions& facades,
                      FacadeMesh& scratch, TriangleMesh& mesh) {
    static const auto materials = facade_surface_materials();
    const BuildingWalls walls(b);
    for (size_t w = 0, n = walls.count(); w < n; ++w) {
        Vec2 p, q;
        walls.wall(w, &p, &q);
        const WallInput input = walls.input(w);
        if (p == q || !(input.height > 0)) continue;  // no wall under a roof that starts at the bottom
        scratch.clear();
        const WallLayout layout = make_wall_layout(facades, input);
        const WallFrame frame = wall_frame(p, q, bottom);
        append_wall_mesh(layout, frame, scratch);
        const uint32_t first = static_cast<uint32_t>(mesh.vertex_count());
        for (Vec3 v : scratch.vertices) mesh.add_vertex(v);
        for (size_t t = 0; t < scratch.triangles.size(); ++t) {
            const auto& tri = scratch.triangles[t];
            const FacadeSurface surface = scratch.surfaces[t];
            // A pane's two triangles come together; remember its cell (from its centre) for lit windows.
            if (t % 2 == 0 && (surface == FacadeSurface::Glass || surface == FacadeSurface::BalconyDoor ||
                               surface == FacadeSurface::ShopWindow)) {
                const Vec3 centre = (scratch.vertices[tri[0]] + scratch.vertices[tri[1]] + scratch.vertices[tri[2]]) *
                                    (1.0 / 3);
                const Vec3 local = frame.point_to_local(centre);
                // The centre lies inside its cell; the clamp only guards rounding at the grid's edge.
                const int floor = std::clamp(
                    static_cast<int>(std::floor((local.y - layout.grid_v0) / layout.floor_height)), 0, layout.floors - 1);
                const int slot = std::clamp(
                    static_cast<int>(std::floor((local.x - layout.grid_u0) / layout.slot_width)), 0, layout.slots - 1);
                mesh.pane_cells.push_back({static_cast<uint32_t>(mesh.triangle_count()), static_cast<uint32_t>(w),
                                           static_cast<uint32_t>(floor) * 65536u + static_cast<uint32_t>(slot) + 1});
            }
            mesh.add_triangle(first + tri[0], first + tri[1], first + tri[2], object,
                              materials[static_cast<int>(surface)]);
        }
    }
}

// Buffer sizes for all buildings (facades exact, roofs and undersides a bound), so the buffers
// are allocated once (in huge pages) instead of doubling: at tall heights they hold tens of
// millions of triangles.
void reserve_buildings(const Scene& scene, const FacadeOptions& facades, TriangleMesh& mesh) {
    size_t triangles = 0, vertices = 0;
    for (const Building& b : scene.buildings) {
        if (!has_volume(b)) continue;
        size_t ring_points = b.outer.size();
        for (const Ring& h : b.holes) ring_points += h.size();
        const BuildingWalls walls(b);
        for (size_t w = 0, n = walls.count(); w < n; ++w) {
            const size_t t = wall_triangle_count(make_wall_layout(facades, walls.input(w)));
            triangles += t;
            vertices += 2 * t;  // 4 vertices per rectangle of 2 triangles
        }
        triangles += 2 * (ring_points + 2 * b.holes.size());  // roof and underside
        vertices += 2 * ring_points;
    }
    mesh.reserve(vertices, triangles);
}

// A planar face as triangles, wound counter-clockwise seen from the face's front: triangulated
// in its projection along the dominant axis of its normal (faces may be non-convex).
void add_planar_face(const std::vector<Vec3>& points, uint32_t object, uint16_t material, TriangleMesh& mesh) {
    FacePlane plane;
    if (!face_plane(points, &plane)) return;
    const Vec3 n = plane.normal;
    const double offset = plane.offset;
    const int drop = plane.drop, au = plane.axis_u, av = plane.axis_v;
    Ring flat;
    for (Vec3 p : points) flat.push_back({p[au], p[av]});
    const PolygonTriangulation tri = triangulate_polygon(flat);
    // Points of the triangulation back in 3D: on the face's plane, the same plane the procedural
    // mode intersects.
    const uint32_t first = static_cast<uint32_t>(mesh.vertex_count());
    for (Vec2 q : tri.points) {
        double c[3] = {0, 0, 0};
        c[au] = q.x;
        c[av] = q.y;
        c[drop] = (offset - n[au] * q.x - n[av] * q.y) / n[drop];
        mesh.add_vertex({c[0], c[1], c[2]});
    }
    // The projection keeps the winding when the normal's dropped component is positive
    // (for the x axis dropped the (y, z) frame is right-handed; for y, (x, z) is left-handed).
    const bool keep = (drop == 1) ? n[drop] < 0 : n[drop] > 0;
    for (const auto& t : tri.triangles) {
        if (keep) mesh.add_triangle(first + t[0], first + t[1], first + t[2], object, material);
        else mesh.add_triangle(first + t[0], first + t[2], first + t[1], object, material);
    }
}

Ring oriented(const Ring& ring, bool counter_clockwise) {
    Ring r = ring;
    if ((signed_area(r) > 0) != counter_clockwise) std::reverse(r.begin(), r.end());
    return r;
}

}  // namespace

std::vector<Vec3> lifted_face(const RoofFace& face, double ground_z) {
    std::vector<Vec3> points = face.points;
    for (Vec3& p : points) p.z += ground_z;
    return points;
}

uint16_t roof_face_material(const RoofFace& face) { return face.kind == RoofFaceKind::Gable ? kFacade : kRoof; }

TriangleMesh build_stored_buildings(const Scene& scene, const FacadeOptions& facades, Progress* progress) {
    TriangleMesh mesh;
    mesh.kind = ObjectKind::Building;
    reserve_buildings(scene, facades, mesh);
    FacadeMesh scratch;
    for (uint32_t index = 0; index < scene.buildings.size(); ++index) {
        if (progress) progress->advance();
        const Building& b = scene.buildings[index];
        if (!has_volume(b)) continue;
        const double ground = building_base(scene, b);
        const double bottom = ground + b.min_height, top = ground + b.height;
        add_facade_walls(b, index, bottom, facades, scratch, mesh);

        // The footprint's triangles: the flat roof (when there are no roof faces) and the
        // underside of a floating part.
        const bool flat_roof = b.roof_faces.empty(), underside = b.min_height > 0;
        PolygonTriangulation footprint;
        if (flat_roof || underside) {
            std::vector<Ring> holes;
            for (const Ring& h : b.holes) holes.push_back(oriented(h, false));
            footprint = triangulate_polygon(oriented(b.outer, true), holes);
        }
        if (flat_roof) {
            const uint32_t first_top = static_cast<uint32_t>(mesh.vertex_count());
            for (Vec2 p : footprint.points) mesh.add_vertex({p.x, p.y, top});
            for (const auto& t : footprint.triangles)
                mesh.add_triangle(first_top + t[0], first_top + t[1], first_top + t[2], index, kRoof);
        }
        for (const RoofFace& face : b.roof_faces)
            add_planar_face(lifted_face(face, ground), index, roof_face_material(face), mesh);
        if (underside) {  // a floating part (bridge, overhang)
            const uint32_t first_bottom = static_cast<uint32_t>(mesh.vertex_count());
            for (Vec2 p : footprint.points) mesh.add_vertex({p.x, p.y, bottom});
            for (const auto& t : footprint.triangles)
                mesh.add_triangle(first_bottom + t[0], first_bottom + t[2], first_bottom + t[1], index,
                                  kFacade);
        }
    }
    return mesh;
}

}  // namespace citygen
