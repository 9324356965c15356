// The ground everything in the render stands on: the scene's height field drawn as triangles
// (two per cell, split along the cell's south-west to north-east diagonal), or the flat ground
// plane at scene.ground.z when the scene has no field. Both geometry modes draw this surface
// and every class that stands on the ground asks ground_height, so nothing floats or sinks.
#pragma once

#include <cstdint>

#include "common/scene.h"
#include "render/geometry/triangulate_polygon.h"

namespace citygen {

// The height of the drawn ground at (x, y): the field's node heights interpolated linearly on
// the cell's triangle (equal to HeightField::at at the nodes; beyond the grid the edge's
// height), or scene.ground.z without a field.
double ground_height(const Scene& scene, double x, double y);

// The same surface on one field (no scene): the triangle rule shared by the stored mesh, the
// procedural intersector and ground_height.
double field_surface_height(const HeightField& field, double x, double y);

// Where the map has sea, the DEM's coarse cells and its coast often stand above sea level and
// would cover the sea surface (drawn flat at its level): nodes inside a Sea land-cover polygon
// (holes excepted) are lowered to kSeaFloor. Render applies it once after loading a scene, so
// every user of ground_height sees the same field. Without a field it does nothing.
constexpr double kSeaFloor = -1.0;  // metres, relative to the field's reference (sea level)
void sink_field_under_sea(Scene& scene);

// Node (i, j) of the field in scene coordinates.
inline Vec3 field_node(const HeightField& field, uint32_t i, uint32_t j) {
    return {field.origin.x + i * field.cell, field.origin.y + j * field.cell,
            static_cast<double>(field.heights[static_cast<size_t>(j) * field.nx + i])};
}

// The lowest ground point under a building's outer ring (its vertices, where its edges cross
// the field's cell lines and diagonals, and the nodes inside it): the base its walls stand on,
// so they reach the ground all round. Shared by both modes, lights and facade frames.
double building_base(const Scene& scene, const Building& building);

// The ring with its edges cut where they cross the field's cell lines and diagonals (unchanged
// without a field): between its points the drawn ground under an edge is linear (curb faces).
Ring split_at_field_lines(const Scene& scene, const Ring& ring);

// A flat polygon laid on the field: triangulated, each triangle cut into its pieces over the
// field's cell triangles, each point's z = ground_height + lift, so the surface lies exactly
// `lift` above the drawn ground (triangles counter-clockwise, front side up). Callers keep their
// flat polygon without a field.
struct DrapedPolygon {
    std::vector<Vec3> points;
    std::vector<std::array<uint32_t, 3>> triangles;
};
DrapedPolygon drape_polygon(const Scene& scene, const Ring& outer, const std::vector<Ring>& holes, double lift);

}  // namespace citygen
