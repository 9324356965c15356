// The ground the scene stands on, one definition for both programs: the scene's height field
// as triangles (two per cell, split along the cell's south-west to north-east diagonal), or the
// flat ground plane at scene.ground.z when the scene has no field. Render draws this surface
// and stands everything on it; osmparse's outputs (GeoJSON z) give the same heights.
#pragma once

#include <cstdint>
#include <vector>

#include "common/geometry.h"
#include "common/scene.h"

namespace citygen {

// Node (i, j) of the field in scene coordinates.
inline Vec3 field_node(const HeightField& field, uint32_t i, uint32_t j) {
    return {field.origin.x + i * field.cell, field.origin.y + j * field.cell,
            static_cast<double>(field.heights[static_cast<size_t>(j) * field.nx + i])};
}

// The field's surface at (x, y): its node heights interpolated linearly on the cell's triangle
// (equal to HeightField::at at the nodes; beyond the grid the edge's height), relative to the
// field's reference altitude.
double field_surface_height(const HeightField& field, double x, double y);

// The height of the ground at (x, y): field_surface_height, or scene.ground.z without a field.
double ground_height(const Scene& scene, double x, double y);

// Where the segment a->b crosses the field's grid lines and diagonals, as parameters in (0, 1),
// ascending: between them the field's surface under the segment is linear.
std::vector<double> field_line_crossings(const HeightField& field, Vec2 a, Vec2 b);

// The lowest ground point under a building's outer ring (its vertices, where its edges cross
// the field's cell lines and diagonals, and the nodes inside it): the base its walls stand on,
// so they reach the ground all round. scene.ground.z without a field.
double building_base(const Scene& scene, const Building& building);

// Piers, quays and breakwaters (paved land cover) reaching into the sea stand on the field at
// kPierDeck above sea level (the field's reference, where the sea is drawn): osmparse raises the
// field's nodes under them (fit_terrain.h) and render leaves those nodes when it lowers the field
// under the sea (render/geometry/ground.h), so the pier's surface is flat to its edge.
constexpr double kPierDeck = 1.0;

// The field's nodes a pier holds, one flag per node: inside a paved land cover polygon inside
// the sea, or within a cell's diagonal of its outline there (so every cell the pier is draped
// over is flat). Empty without a field or without sea.
std::vector<uint8_t> pier_nodes(const HeightField& field, const std::vector<LandCover>& land_cover);

// One flag per node of the field: inside a sea polygon (holes excepted).
std::vector<uint8_t> sea_nodes(const HeightField& field, const std::vector<LandCover>& land_cover);

}  // namespace citygen
