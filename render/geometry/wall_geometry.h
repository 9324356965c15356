// Retaining walls (common/retaining_wall.h): each wall a slab along its line, from under the low
// side's ground to a parapet above the high side's, its faces the same in both geometry modes
// (stored as triangles, procedural as planar faces of an Embree user geometry). Object index:
// the wall's index in scene.retaining_walls. Without a field there are no walls to draw.
#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "common/scene.h"
#include "render/geometry/planar_face.h"

namespace citygen {

// The material a wall is drawn with, from its material tag: stone, brick, wood, else concrete.
uint16_t retaining_wall_material(WallMaterial material);

// A wall's faces: along each pair of consecutive stations its two faces and its top (two
// triangles: a mitred top is not planar), and a cap at each end of an open line. No underside:
// the foot is under the ground.
std::vector<PlanarFace> retaining_wall_faces(const Scene& scene, const RetainingWall& wall);

TriangleMesh build_stored_retaining_walls(const Scene& scene);
std::unique_ptr<ProceduralGeometry> build_procedural_retaining_walls(const Scene& scene);

}  // namespace citygen
