// The terrain stage (--dem): the DEMs read over the scene's bounds, their voids filled, as the
// scene's height field. docs/terrain.md describes the field and the rules.
#pragma once

#include <vector>

#include "common/scene.h"
#include "osmparse/core/params.h"
#include "common/projection.h"
#include "osmparse/core/report.h"
#include "osmparse/terrain/dem_grid.h"

namespace citygen {

// Per node of the grid, 1 inside the scene's sea (land cover class Sea): where a void is sea.
std::vector<uint8_t> sea_mask(const DemGrid& grid, const std::vector<LandCover>& land_cover);

// The height field over header's bounds: the field's heights are relative to its reference
// altitude, the lowest height rounded down to a metre but never below sea level (so a coastal
// scene's sea stays at z = 0). Counts nodes, voids and findings about the DEMs in the report.
// Throws Error (one line) when a DEM cannot be read or none overlaps the bounds.
HeightField build_terrain(const SceneHeader& header, const Projection& projection,
                          const std::vector<LandCover>& land_cover, const TerrainParams& params,
                          ParseReport& report);

}  // namespace citygen
