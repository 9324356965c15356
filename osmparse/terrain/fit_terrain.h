// Fitting the height field to what lies on it (issue 22, items 2 and 4), after the DEM is read:
// - roads, paths and rails are laid into the ground: under each one the field is level across
//   it at the height of its centreline's longitudinal profile (the field smoothed along it),
//   and a shoulder beyond blends that back into the DEM (cut where the ground is above the
//   road, fill where it is below);
// - still water (lakes, ponds, reservoirs) is levelled at its shore's lowest height.
// Render drapes every road, joint, sidewalk, path and land cover polygon on the field (common/
// ground.h), so the pieces meet without a step and the ground never covers a road nor leaves
// one floating. docs/terrain.md, "Fitted to roads and water".
#pragma once

#include <algorithm>

#include <cstdint>
#include <vector>

#include "common/scene.h"
#include "osmparse/core/report.h"

namespace citygen {

// Gaussian scale (metres) of the smoothing a centreline's profile is taken from: a DEM's pixel
// noise and what a fine surface model holds (cars, walls, hedges) are shorter than this, a
// road's vertical curves longer; a hairpin's two legs, 20 m or more apart, stay apart.
constexpr double kProfileSmoothing = 10;
// Width (metres) of the shoulder that blends a road's level back into the DEM. At 10 m a cut or
// fill of 2 m slopes 1:5, a gentle bank.
constexpr double kShoulderWidth = 10;
// The shoulder on `field`: kShoulderWidth, at least two cells.
inline double shoulder_width(const HeightField& field) { return std::max(kShoulderWidth, 2 * field.cell); }
// How closely a node `beyond` metres past what the ground is fitted to (a road's level, a
// stair's line, a wall's foot) follows it: 1 there, easing to 0 at the shoulder's end.
inline double shoulder_weight(double beyond, double shoulder) {
    const double s = std::clamp(beyond / shoulder, 0.0, 1.0);
    return 1 - s * s * (3 - 2 * s);
}
// A water polygon whose shore falls by more than this (metres) is a river down a valley, not
// still water: levelling it at its lowest shore would dig a canyon, so it is left draped.
constexpr double kMaxStillWaterFall = 5;

// The ways and the parts of their cross-section the field is fitted to.
struct FitWidths {
    double sidewalk = 2;  // a road's sidewalk beyond its carriageway, when it has one
};

// Below a bridge's deck the field keeps this much air under its slab (metres).
constexpr double kUnderDeckGap = 0.5;

// Lays roads and paths into the field and counts what was fitted in the report. A bridge is not
// fitted: it keeps its own deck (common/bridge_deck.h) and the field under it is carved below
// the deck; steps are left on the DEM (render draws the steep ones as a stair: note_steps),
// but the DEM that would bury a steep stair is cut down to the line between its ends.
void fit_terrain_to_ways(HeightField& field, const std::vector<RoadEdge>& roads,
                         const std::vector<PathEdge>& paths, const FitWidths& widths, ParseReport& report);

// One flag per node of the field: within a road's or path's corridor (every one's: bridges and
// steps too), the nodes fit_terrain_to_ways levels or keeps, which what is fitted after it (the
// retaining walls' steps) leaves as they are.
std::vector<uint8_t> way_corridor_nodes(const HeightField& field, const std::vector<RoadEdge>& roads,
                                        const std::vector<PathEdge>& paths, const FitWidths& widths);

// Counts the steps edges render draws as a stair on the finished field (common/stairs.h's
// plan_stair: steeper than kStairMinGrade between their ends) and those it drapes.
void note_steps(const Scene& scene, ParseReport& report);

// Levels still water (land cover class Water) at its shore's lowest height, with the nodes
// within a cell outside its shore, so the cells it is draped over are flat.
void level_still_water(HeightField& field, const std::vector<LandCover>& land_cover, ParseReport& report);

// Sets the nodes piers hold in the sea (common/ground.h's pier_nodes) to kPierDeck, so piers,
// quays and breakwaters are flat surfaces above the water and what stands on them stands there.
void raise_piers(HeightField& field, const std::vector<LandCover>& land_cover, ParseReport& report);

}  // namespace citygen
