// Roof faces from a footprint and a roof shape: pure geometry, no tags (build_roofs.cpp reads
// those). Every face is a planar polygon counter-clockwise seen from outside, lies over the
// footprint and between the eaves and the top.
#pragma once

#include <vector>

#include "common/geometry.h"
#include "common/scene.h"
#include "osmparse/core/report_reasons.h"

namespace citygen {

struct RoofSpec {
    RoofShape shape = RoofShape::Flat;
    double eaves_z = 0;       // top of the walls
    double height = 0;        // the roof rises this far above the eaves
    bool has_direction = false;
    Vec2 direction;           // unit: the way the (main) slope faces downhill (roof:direction)
    bool across = false;      // roof:orientation=across: ridge along the short side
};

// The roof faces (kind Roof) over `outer` (CCW) with `holes` (CW), without gable walls.
// Ridge shapes (gabled, half-hipped, gambrel, mansard, round) need a footprint without holes
// that fills at least 85% of its minimum-area rectangle; centred ones (pyramidal, dome, onion)
// a convex footprint; a skillion no holes. On any other footprint they are built hipped from
// the straight skeleton, and `built` says so.
// Returns false, with `why` set (a "could not build" note), when no roof can be built on this
// footprint.
bool make_roof_faces(const Ring& outer, const std::vector<Ring>& holes, const RoofSpec& spec,
                     std::vector<RoofFace>* faces, RoofShape* built, ReportReason* why);

// The vertical walls between the eaves and the roof edge (kind Gable): for each footprint edge
// whose roof edge rises above eaves_z, one polygon from the eaves up to the roof edge.
std::vector<RoofFace> gable_walls(const Ring& outer, const std::vector<Ring>& holes,
                                  const std::vector<RoofFace>& roof, double eaves_z);

// The parts of a simple counter-clockwise ring where dot(normal, p) <= offset (several when a
// non-convex ring falls apart). False when the cut is degenerate.
bool split_off(const Ring& ring, Vec2 normal, double offset, std::vector<Ring>* pieces);

// Whether every point of the face lies within `tolerance` of its (Newell) plane, and it has area.
bool face_is_planar(const RoofFace& face, double tolerance);

// Dimensions the roof rules use: the footprint's extent along and across its ridge axis.
struct RoofFrame {
    Vec2 centre, along, across;  // origin of s and t (a footprint vertex); unit axes, across = perp_left(along)
    double s0 = 0, s1 = 0, t0 = 0, t1 = 0;  // extents of the footprint along / across
    double width() const { return t1 - t0; }
    double length() const { return s1 - s0; }
};
// Ridge along the long side of the minimum-area bounding rectangle (or the short side when
// `across`); with a direction, the ridge is perpendicular to it.
RoofFrame roof_frame(const Ring& outer, const RoofSpec& spec);

}  // namespace citygen
