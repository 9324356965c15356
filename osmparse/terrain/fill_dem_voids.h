// Filling the holes of a DEM grid (no GDAL here): every node gets a height. docs/terrain.md
// gives the rules and why.
#pragma once

#include <cstdint>
#include <vector>

#include "osmparse/terrain/dem_grid.h"

namespace citygen {

// Sea level on a void's rim: SRTM's sea reads 0 with a few metres of noise, mostly below 0.
// Depressions deeper than this (the Dead Sea's shore, the Caspian's) are land.
constexpr double kCoastRimMin = -20, kCoastRimMax = 1;

struct VoidCounts {
    int64_t out_of_range = 0;  // heights beyond kMinAltitude..kMaxAltitude, treated as voids
    int64_t filled = 0;        // void nodes filled from their neighbours
    int64_t sea = 0;           // void nodes at the coast, set to sea level (0 m)
    int64_t outside = 0;       // nodes outside every DEM, given the height of the nearest covered node
};

// Gives every node of `grid` a height. A node inside a DEM without a height (NaN, or beyond
// kMinAltitude..kMaxAltitude) is a void. A void node in the scene's sea (`sea`: 1 per node
// inside it; empty: none) is sea level (0 m); so is each 8-connected region of the other void
// nodes whose rim (the known nodes around it) is at least half at sea level: a void at the
// coast. Any other region is filled from the heights around it (layer by layer from its rim,
// then smoothed towards the harmonic fill, which continues a slope through the hole: a void in
// a cliff above the sea keeps the cliff). A node outside every DEM takes the height of the
// nearest covered node, so the ground stays flat beyond a DEM's edge. Throws Error when no node
// has a height to start from.
VoidCounts fill_dem_voids(DemGrid& grid, const std::vector<uint8_t>& sea);

}  // namespace citygen
