// Stage: heights where the map has none. Runs after build_buildings, over all buildings at
// once, because the tagged heights of neighbours are one of the rules.
#pragma once

#include <vector>

#include "params.h"
#include "report.h"
#include "scene.h"

namespace citygen {

// Replaces the random height of every ground-standing building with nothing tagged
// (height_source Random, min_height 0) by the first rule that applies; height_rule records it:
//  1. TypeAndArea for sure things: a footprint under 30 m2, or a garage/shed/carport/kiosk-like
//     type, is a one-storey shed; a house-like type is a two-storey house (both rules first
//     because a neighbour's height says little about a garage beside a tower);
//  2. Neighbours: the distance-weighted median height of the nearest (up to 8) buildings within
//     150 m whose height is tagged (height or building:levels), preferring ones of the same type;
//  3. TypeAndArea: a height by building type (apartments, office, industrial, ...) and, for
//     `yes`/unknown types, by footprint area;
//  4. Random: the seeded random height in [random_min_height, random_max_height] stays (only
//     reached for types the table does not know, with no tagged neighbour).
// Each guess is jittered by up to +-10% (seeded per building) so a street is not one height.
// Levels are recomputed from the new height. Counts go to "building heights" in the report.
void infer_heights(std::vector<Building>& buildings, const BuildingParams& params, ParseReport& report);

// Rule 1 and 3 alone (exposed for tests): the height of a building of `type` with a footprint of
// `area` m2, or 0 when the type says nothing; `sure` tells whether the rule beats neighbours.
double height_by_type_and_area(const std::string& type, double area, bool* sure);

}  // namespace citygen
