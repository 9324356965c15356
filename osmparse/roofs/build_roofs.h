// Stage 4: roofs. roof:shape and its companions -> planar roof faces and gable walls on every
// building (after the heights are final).
#pragma once

#include <vector>

#include "common/scene.h"
#include "osmparse/buildings/building_tags.h"
#include "osmparse/core/params.h"
#include "osmparse/core/report.h"

namespace citygen {

// Sets roof_shape, roof_height, roof_inferred and roof_faces of every building:
//  - shape: roof:shape (flat, skillion, gabled, hipped, half-hipped, pyramidal, gambrel, mansard,
//    dome, onion, round, and a few synonyms); an unknown value gives a flat roof (counted);
//    untagged: default_roof() below (roof_inferred = true);
//  - height: roof:height, else roof:levels x level_height, else from the pitch (roof:angle, else
//    the shape's default pitch) and the footprint's width. A tagged height includes the roof; a
//    height from building:levels gets the roof on top of its storeys. A roof:height above the
//    building is clamped to it (counted); a bad roof:angle (outside (0, 85] degrees) is ignored
//    (counted); a derived roof takes at most 3/4 of the building's height;
//  - faces: make_roof_faces() plus gable_walls(); a shape that cannot be built, or whose faces
//    fail the checks (planar, between eaves and height, over the footprint), gives a flat roof
//    (counted under "roofs").
void build_roofs(std::vector<Building>& buildings, const BuildingTagIndex& tags, const BuildingParams& params,
                 ParseReport& report);

// The documented default for untagged roofs, by building type, footprint area and height
// (seeded per building): houses, farms, churches, huts pitched (mostly gabled, some hipped or
// half-hipped); garages and sheds flat, gabled or skillion; small `yes`/`residential` buildings
// up to 13 m pitched six times in ten, small apartment blocks up to 20 m three in ten; everything
// else (commercial, industrial, large or tall buildings, building parts, raised parts) flat.
// Also returns the pitch in degrees for pitched shapes.
RoofShape default_roof(const Building& building, double area, uint64_t seed, double* pitch_deg);

// roof:shape text -> shape; false for unknown values.
bool parse_roof_shape(const char* text, RoofShape* shape);
// roof:direction: degrees (0 = north, clockwise) or a compass point (N, NNE, ...); false otherwise.
bool parse_compass_direction(const char* text, double* degrees);

// Whether a face is planar, between z_min and z_max and over the footprint (within tolerance).
bool roof_face_is_valid(const RoofFace& face, const Building& building, double z_min, double z_max);

}  // namespace citygen
