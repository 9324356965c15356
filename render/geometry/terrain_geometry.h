// The terrain in both geometry modes when the scene has a height field (ground.h): the field as
// two triangles per cell, and a skirt of flat quads from the field's border out to
// terrain_extent at the border's heights, so the horizon stays where the flat plane put it.
//   stored:     the triangles and skirt as a mesh (build_stored_terrain).
//   procedural: a user geometry keeping only the heights; one primitive per block of
//               kTerrainBlock x kTerrainBlock cells, whose callback walks the block's cells along
//               the ray and intersects the same two triangles per cell; one primitive per skirt quad.
//               A height range per block and per group of 4 x 4 cells lets the walk cross the
//               groups the ray passes above (or below) in one step, and a cell's own nodes'
//               range spares the triangle tests where the ray does not come down to it.
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "common/scene.h"
#include "render/scene/render_scene.h"
#include "render/scene/triangle_mesh.h"

namespace citygen {

constexpr uint32_t kTerrainBlock = 16;

// The skirt's quads, each counter-clockwise seen from above (planar: a border edge moved straight
// out, or a corner at its node's height).
std::vector<std::array<Vec3, 4>> terrain_skirt(const Scene& scene);
// Quad k of terrain_skirt(scene) for `field` reaching out to `extent` (terrain_extent), of
// terrain_skirt_count(field): what the procedural terrain derives instead of storing them.
size_t terrain_skirt_count(const HeightField& field);
std::array<Vec3, 4> terrain_skirt_quad(const HeightField& field, const Box2& extent, size_t k);

// The field's triangles and the skirt, all object 0, material kGround. The scene must have a field.
TriangleMesh build_stored_field_terrain(const Scene& scene);

std::unique_ptr<RenderGeometry> build_procedural_field_terrain(const Scene& scene);

}  // namespace citygen
