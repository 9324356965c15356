// Triangulating the facade rules: the stored geometry mode's walls.
//
// Every rectangle from cell_rects()/margin_rects() (facade.h) becomes two triangles wound so
// that their geometric normal is the rectangle's normal. Nothing else is added, so the
// triangles are exactly the surfaces wall_intersect.h hits. Roofs and flat polygons are the
// renderer's business.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "render/facade/facade.h"

namespace citygen {

struct FacadeMesh {
    std::vector<Vec3> vertices;                     // world (or wall-local) positions
    std::vector<std::array<uint32_t, 3>> triangles;
    std::vector<FacadeSurface> surfaces;            // one per triangle

    void clear() { vertices.clear(); triangles.clear(); surfaces.clear(); }
};

// Appends the wall's triangles, placed with `frame` (use WallFrame{} for wall-local coordinates).
void append_wall_mesh(const WallLayout& layout, const WallFrame& frame, FacadeMesh& mesh);

// How many triangles append_wall_mesh adds, without building them.
size_t wall_triangle_count(const WallLayout& layout);

}  // namespace citygen
