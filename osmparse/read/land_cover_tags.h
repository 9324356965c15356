// Which OSM areas are land cover, and of which class: the read stage keeps these areas
// (read_osm), the land cover stage builds them (osmparse/map/build_land_cover.h).
#pragma once

#include <optional>
#include <vector>

#include "common/scene.h"
#include "osmparse/core/osm_data.h"

namespace citygen {

// The land cover class of an area's tags, or nullopt when it has none. The one table:
//   water     natural=water, waterway=riverbank, landuse=basin|reservoir, leisure=swimming_pool
//   green     leisure=park|garden|pitch|playground, landuse=grass|meadow|village_green|cemetery|
//             recreation_ground, natural=grassland|heath|scrub
//   forest    natural=wood, landuse=forest
//   paved     highway=pedestrian (area=yes) or area:highway=*, place=square, amenity=parking,
//             man_made=pier|breakwater (is_pier: kept only on a height field, build_land_cover.h)
//   sand      natural=sand|beach
//   farmland  landuse=farmland|orchard|vineyard|allotments
//   built_up  landuse=residential|commercial|retail|industrial (ground paving)
// The sea is not an area in OSM: assemble_sea.h builds it from natural=coastline.
std::optional<LandCoverClass> land_cover_class(const OsmTags& tags);

// man_made=pier or breakwater: a walkable surface above the water.
bool is_pier(const OsmTags& tags);

// Every tag key land_cover_class reads (read_osm hands areas with these keys to the
// multipolygon assembler).
const std::vector<const char*>& land_cover_keys();

}  // namespace citygen
