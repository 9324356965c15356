// Planar faces built the same for both geometry modes (bridges, stairs, retaining walls): stored
// as a fan of triangles, procedural as user-geometry faces.
#pragma once

#include <cstdint>
#include <vector>

#include "common/geometry.h"
#include "render/geometry/procedural_geometry.h"
#include "render/scene/triangle_mesh.h"

namespace citygen {

// A planar convex polygon, front side counter-clockwise.
struct PlanarFace {
    std::vector<Vec3> points;
    uint16_t material;
};

// The faces as object `object`'s triangles, or its procedural faces.
void add_faces(const std::vector<PlanarFace>& faces, uint32_t object, TriangleMesh& mesh);
void add_faces(const std::vector<PlanarFace>& faces, uint32_t object, ProceduralGeometry& geometry);

}  // namespace citygen
