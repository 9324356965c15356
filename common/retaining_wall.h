// Retaining walls on a height field (format 1.2, barrier=retaining_wall), one rule for both
// programs: a slab kRetainingWallThickness thick along the wall's line, from under the low side's
// ground up to kRetainingWallParapet above the high side's, so it hides the slope the field
// steps down in between them (osmparse lowers the low side, osmparse/terrain/
// retaining_wall_steps.h). Render draws the slab in both geometry modes (render/geometry/
// wall_geometry.h); the GeoJSON gives its top. docs/terrain.md, "Retaining walls".
#pragma once

#include <vector>

#include "common/geometry.h"
#include "common/scene.h"

namespace citygen {

// The slab's thickness, centred on the line (metres).
constexpr double kRetainingWallThickness = 0.3;
// How far the wall's top stands above the highest ground beside it: a low parapet, so the wall
// reads as one from the high side too.
constexpr double kRetainingWallParapet = 0.2;
// How far its foot reaches below the lowest ground at its faces, so no gap opens under it where
// the drawn ground between two stations dips below their line.
constexpr double kRetainingWallFooting = 0.5;

// A cross-section of the slab: its two faces' points (left: the high side, right: the low side;
// mitred at the line's vertices) and the heights of its foot and top there.
struct WallStation {
    Vec2 left, right;
    double bottom = 0, top = 0;
};

// The slab's cross-sections along the wall, in the line's direction: at its vertices and where
// the line or its faces cross the field's cell lines and diagonals, so between two stations the
// drawn ground along each face is linear. The top is the highest of the ground at both faces and
// a cell's diagonal out on the high side (where the field is the high side's own, not the slope
// down to the low side) plus the parapet; the foot the lowest ground at the faces less the
// footing. Empty without a field (walls are kept only with one) or for a line of one point.
std::vector<WallStation> wall_stations(const Scene& scene, const RetainingWall& wall);

}  // namespace citygen
