// Stage 5: colours and materials of walls and roofs, from the map where it says, else seeded,
// plausible variety by building type (after roofs: a pitched roof is tiled, a flat one is not).
#pragma once

#include <vector>

#include "common/scene.h"
#include "osmparse/buildings/building_tags.h"
#include "osmparse/core/params.h"
#include "osmparse/core/report.h"

namespace citygen {

// Sets wall_colour, roof_colour, colour_inferred, wall_material and roof_material:
//  - building:material (or building:facade:material) and roof:material, a few synonyms
//    accepted; unknown values are counted and replaced by the default;
//  - building:colour and roof:colour (parse_colour.h); bad values are counted and replaced;
//  - defaults, seeded per building: the wall material by type (houses plaster or brick,
//    apartments mostly plaster, offices and shops concrete, tall offices glass, industry metal
//    or concrete, churches stone or brick, sheds wood or concrete), the roof material by shape
//    (pitched: tiles, slate or metal; flat: tar paper or concrete), and the colour from a
//    palette of that material (plaster in several tones, brick reds, concrete greys, ...).
void choose_colours_and_materials(std::vector<Building>& buildings, const BuildingTagIndex& tags,
                                  const BuildingParams& params, ParseReport& report);

bool parse_wall_material(const char* text, WallMaterial* material);
bool parse_roof_material(const char* text, RoofMaterial* material);

}  // namespace citygen
