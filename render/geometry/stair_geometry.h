// Steep steps on a height field drawn as a stair (the rule: common/stairs.h) instead of a strip
// draped on the ground: a horizontal tread per step across the strip, a vertical riser between
// treads, and side faces from every tread's outline down into the ground, so nothing floats
// where the ground falls away beside it. Both geometry modes build the same faces (stored as
// triangles, procedural as planar faces) with the path's object index.
#pragma once

#include <cstdint>
#include <vector>

#include "common/stairs.h"
#include "render/geometry/planar_face.h"

namespace citygen {

// Side faces reach this far below the lowest ground under their edge, so no gap opens where
// the ground between the cell lines dips.
constexpr double kStairFooting = 0.5;

// The stair's faces over the strip `quad`, its treads `lift` above the plan's heights: planar
// convex polygons, front side counter-clockwise (treads up, risers towards the low end, side
// faces out).
std::vector<PlanarFace> stair_faces(const Scene& scene, const StairPlan& plan, const Ring& quad, double lift,
                                    uint16_t material);

// Adds path `index` as a stair if plan_stair draws it as one; false (nothing added) otherwise.
bool add_stair(const Scene& scene, uint32_t index, double lift, uint16_t material, TriangleMesh& mesh);
bool add_stair(const Scene& scene, uint32_t index, double lift, uint16_t material, ProceduralGeometry& geometry);

}  // namespace citygen
