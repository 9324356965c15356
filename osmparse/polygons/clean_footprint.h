// Footprint clean-up: turns an OSM outline (outer ring + holes, local metres) into
// simple, correctly oriented polygons that later stages can extrude and triangulate.
#pragma once

#include <vector>

#include "common/geometry.h"
#include "osmparse/core/params.h"
#include "osmparse/core/report.h"

namespace citygen {

struct Footprint {
    Ring outer;               // simple, CCW, area >= min_area
    std::vector<Ring> holes;  // simple, CW, strictly inside outer, not touching each other
};

// Vertices closer than this (metres) are one vertex; a vertex this close to the line
// through its neighbours is collinear (or a spike) and is dropped.
constexpr double kFootprintTolerance = 0.01;

// The scene stores float32 coordinates. Cleaning works on values already rounded to
// float, so the rings that were checked are exactly the rings that are stored.
// The float goes through a volatile store: gcc 12.2 at -O2 drops a paired
// double->float->double conversion when it vectorizes the pair, so release builds skipped the
// rounding and gave other scenes than -O1, sanitizer or clang builds. A volatile float must be
// stored and reloaded as a float, whatever the optimizer does.
inline double round_to_float(double v) {
    volatile float rounded = static_cast<float>(v);
    return rounded;
}
inline Vec2 round_to_stored_precision(Vec2 p) { return {round_to_float(p.x), round_to_float(p.y)}; }

// The whole clean-up of one polygon, in this order:
//  1. drop repeated vertices (closer than kFootprintTolerance) and collinear ones or spikes;
//  2. merge runs of consecutive edges whose directions all lie within simplify_angle_deg
//     of each other into one edge (kept only if it leaves the ring simple);
//  3. a ring that is still self-intersecting or self-touching is split at its crossings
//     into simple pieces (a bow-tie becomes two triangles; a piece inside another becomes
//     its hole); pieces that cannot be made simple are dropped. The split is CGAL's
//     arrangement, and the pieces are simplified together (CGAL) so they cannot overlap;
//  4. orient outers CCW, holes CW (CGAL's exact orientation);
//  5. drop holes that are not simple, too small, outside or touching the outline, or
//     overlapping another hole; drop polygons whose area is below min_area. A polygon that
//     loses a hole only because step 2 merged its rings one by one assigns its holes again
//     on the unmerged rings and merges them all together with CGAL, which keeps them apart.
//  6. check every polygon with CGAL (is_valid_polygon_with_holes) and drop any that fails.
// Every decision above is exact (osmparse/polygons/exact_predicates.h) but for the angle
// threshold of step 2, whose result is checked exactly. Returns zero or more polygons
// (usually one). Every drop is counted in `report` under `kind` (outer rings) or holes_row(kind).
std::vector<Footprint> clean_footprint(const Ring& outer, const std::vector<Ring>& holes,
                                       const BuildingParams& params, ParseReport& report, ReportKind kind);

// The report row of the holes of `kind`'s outlines: buildings and their parts count theirs
// under building holes. Throws std::invalid_argument for a kind clean_footprint is not given.
ReportKind holes_row(ReportKind kind);

// The steps, exposed for tests.
Ring remove_repeated_and_collinear(Ring ring, double tolerance = kFootprintTolerance);
Ring merge_small_turns(const Ring& ring, double angle_deg);
std::vector<Ring> split_self_intersections(const Ring& ring);

// A point strictly inside a simple ring (either orientation).
Vec2 interior_point(const Ring& ring);

}  // namespace citygen
