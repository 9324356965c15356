// Stage 14: land cover (with the sea, assemble_sea.h). OSM areas (closed ways and
// multipolygons, assembled by libosmium as buildings are) -> cleaned polygons with holes and
// one class each (DESIGN 6b).
#pragma once

#include <optional>
#include <vector>

#include "osm_data.h"
#include "params.h"
#include "projection.h"
#include "report.h"
#include "scene.h"

namespace citygen {

// Report rows and reasons of this stage (areas are counted under read_osm.h's kLandCoverAreas).
inline constexpr char kLandCoverClassPrefix[] = "land cover: ";
inline constexpr char kBeyondSceneLimits[] = "beyond the scene limits (points or extent)";

// The land cover class of an area's tags, or nullopt when it has none. The one table:
//   water     natural=water, waterway=riverbank, landuse=basin|reservoir, leisure=swimming_pool
//   green     leisure=park|garden|pitch|playground, landuse=grass|meadow|village_green|cemetery|
//             recreation_ground, natural=grassland|heath|scrub
//   forest    natural=wood, landuse=forest
//   paved     highway=pedestrian (area=yes) or area:highway=*, place=square, amenity=parking
//   sand      natural=sand|beach
//   farmland  landuse=farmland|orchard|vineyard|allotments
//   built_up  landuse=residential|commercial|retail|industrial (ground paving)
// The sea is not an area in OSM: assemble_sea.h builds it from natural=coastline.
std::optional<LandCoverClass> land_cover_class(const OsmTags& tags);

// Every tag key land_cover_class reads (read_osm hands areas with these keys to the
// multipolygon assembler).
const std::vector<const char*>& land_cover_keys();

// Projects and cleans every land cover area (the footprint clean-up: repeated and collinear
// points, self-intersections, orientation, holes; slivers below params.min_area dropped),
// sorted by (class, OSM identity). Counted under "land cover areas".
std::vector<LandCover> build_land_cover(const OsmData& osm, const Projection& projection,
                                        const BuildingParams& params, ParseReport& report);

// Drops (and counts) polygons beyond the land cover limits of scene_limits.h, which the
// scene loader would refuse: a ring with too many points or wider than a region.
std::vector<LandCover> drop_land_cover_beyond_limits(std::vector<LandCover> cover, ParseReport& report);

}  // namespace citygen
