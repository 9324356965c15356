// The render-only parts of the ground (common/ground.h holds the surface both programs share):
// the field lowered under the sea, ring edges cut at the field's cell lines, flat polygons draped
// on the drawn ground. Every class that stands on the ground asks ground_height, so nothing
// floats or sinks.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "common/ground.h"
#include "common/scene.h"
#include "render/geometry/triangulate_polygon.h"

namespace citygen {

// Where the map has sea, the DEM's coarse cells and its coast often stand above sea level and
// would cover the sea surface (drawn flat at its level): nodes inside a Sea land-cover polygon
// (holes excepted) are lowered to kSeaFloor, but those a pier holds (common/ground.h's
// pier_nodes). Render applies it once after loading a scene, so every user of ground_height
// sees the same field. Without a field it does nothing.
constexpr double kSeaFloor = -1.0;  // metres, relative to the field's reference (sea level)
void sink_field_under_sea(Scene& scene);

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
