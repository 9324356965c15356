// Road markings and asphalt grain, painted at shading time from the few numbers the scene
// keeps per road (lanes, centre line, edge lines) and per crossing, in both geometry modes:
// the road geometry is wrapped so a hit on asphalt may turn into a hit on paint.
#pragma once

#include <memory>
#include <vector>

#include "common/scene.h"
#include "render/scene/render_scene.h"

namespace citygen {

// What the paint of one road is worked out from: the ends of its centreline and its lanes.
struct RoadPaint {
    Vec2 a, b;  // the centreline's first and last points
    double width = 0;
    int lanes_forward = 0, lanes_backward = 0;
    CentreLine centre_line = CentreLine::None;
    bool edge_lines = false, cycle_lane_left = false, cycle_lane_right = false;
    bool straight = false;  // a centreline of two points or more (else: asphalt only)
};
RoadPaint road_paint(const RoadEdge& road);

// Paint and asphalt at point p of a road; `crossings` are the scene.crossings on that road. Centre
// lines: dashed 3 m on / 6 m off, solid, or double; lane dividers dashed; edge lines 0.3 m inside
// the edge; cycle lanes 1.5 m wide at the edge behind a solid line (the motor lanes share the
// rest); lines 12-15 cm wide; zebra stripes 0.5 m wide, 0.5 m apart, 3 m long along the road; stop
// lines 0.4 m. Elsewhere asphalt with a 4 cm speckle of lighter grain.
uint16_t road_surface_material(const RoadPaint& road, const std::vector<const Crossing*>& crossings, Vec2 p);

// Asphalt grain alone (junction polygons).
uint16_t asphalt_grain(Vec2 p);

// Wrap road / joint geometry of either mode (the wrapper copies what it needs of `scene`).
std::unique_ptr<RenderGeometry> with_road_markings(std::unique_ptr<RenderGeometry> roads, const Scene& scene);
std::unique_ptr<RenderGeometry> with_asphalt_grain(std::unique_ptr<RenderGeometry> joints);

}  // namespace citygen
