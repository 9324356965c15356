// highway=steps on a height field, one rule for both programs (docs/terrain.md, "Steps"): where
// the ground at a steps edge's two ends rises faster than a ramp may (kStairMinGrade), render
// draws the strip as a stair of equal risers no higher than kStairMaxRiser instead of draping
// it, and osmparse counts those edges in its report.
#pragma once

#include "common/geometry.h"
#include "common/scene.h"

namespace citygen {

// A riser of a comfortable outdoor stair (building codes allow 0.15-0.19 m).
constexpr double kStairMaxRiser = 0.18;
// 1:8, the steepest ramp building codes allow (and only for short rises): mapped steps whose
// ends on the field differ by less are a stepped ramp or the DEM's noise over a short edge, and
// the draped strip shows them as well as a stair of a few flat treads would.
constexpr double kStairMinGrade = 0.125;
// More steps than this on one edge (a rise of 737 m) is no stair: the edge stays draped.
constexpr int kMaxStairSteps = 4096;

// A stair between the two ends of a steps strip: the centres of its end edges (where it meets
// the joint or the next strip, not the centreline's nodes inside the joints) on the ground, low
// end first. Along the strip from `low` to `high`, tread k of `steps` (k = 0 at the low end)
// covers [k, k + 1] * run / steps and stands at z_low + (k + 1) * rise: the first riser rises
// from the low end's ground and the top tread is level with the high end's.
struct StairPlan {
    Vec2 low, high;
    double z_low = 0, z_high = 0;
    int steps = 0;
    double run() const { return length(high - low); }
    double rise() const { return (z_high - z_low) / steps; }
    // The height at `p` on the straight line from the low end to the high end (held level beyond
    // them): at most one riser below the top of the tread drawn over `p` (the GeoJSON's stairs).
    double line_height(Vec2 p) const;
};

// The stair between a path's ends on `field`, what osmparse cuts the ground down to: false
// without a field, for any class but steps, on a deck, for a degenerate strip and where the grade
// between its ends is at most kStairMinGrade.
bool stair_between_ends(const HeightField& field, const PathEdge& path, StairPlan* plan);
// The stair a path is drawn as on the scene's finished field: stair_between_ends, but false where
// the ground along the strip still covers the treads by more than a riser (stands more than two
// risers above the stair's line) over more than half its run: a stair the cut could not free,
// beside or under another way's level corridor, is draped, a slope of steps on the ground rather
// than a stair inside the hill.
bool plan_stair(const Scene& scene, const PathEdge& path, StairPlan* plan);

}  // namespace citygen
