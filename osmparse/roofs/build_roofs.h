// Stage 4: roofs. roof:shape and its companions -> planar roof faces and gable walls on every
// building (after the heights are final).
#pragma once

#include <functional>
#include <optional>
#include <vector>

#include "common/scene.h"
#include "osmparse/buildings/building_tags.h"
#include "osmparse/core/params.h"
#include "osmparse/core/report.h"

namespace citygen {

// Sets roof_shape, roof_height, roof_inferred and roof_faces of every building:
//  - shape: roof:shape (flat, skillion, gabled, hipped, half-hipped, pyramidal, gambrel, mansard,
//    dome, onion, round, and a few synonyms); an unknown value gives a flat roof (counted);
//    untagged: default_roof() below, from the extract's roof_evidence (roof_inferred = true);
//  - height: roof:height, else roof:levels x level_height, else from the pitch (roof:angle, else
//    the shape's default pitch) and the footprint's width. A tagged height includes the roof; a
//    height from building:levels gets the roof on top of its storeys. A roof:height above the
//    building is clamped to it (counted); a bad roof:angle (outside (0, 85] degrees) is ignored
//    (counted); a derived roof takes at most 3/4 of the building's height;
//  - faces: make_roof_faces() plus gable_walls(); a shape that cannot be built, or whose faces
//    fail the checks (planar, between eaves and height, over the footprint), gives a flat roof
//    (counted under ReportKind::Roofs).
// `evidence`: the extract's roof_evidence when `buildings` is only a part of it (a slice, the
// empty blocks' buildings); by default that of `buildings` and `tags`.
struct RoofEvidence;
void build_roofs(std::vector<Building>& buildings, const BuildingTagIndex& tags, const BuildingParams& params,
                 ParseReport& report, const RoofEvidence* evidence = nullptr);

// The groups of buildings whose untagged roofs may be pitched: churches and farm buildings
// (church, chapel, cathedral, barn, farm_auxiliary, stable, cowshed); houses (house, detached,
// semidetached_house, terrace, bungalow, farm, villa, cabin, hut, static_caravan, dormitory);
// sheds (garage, garages, shed, carport); small blocks (`yes`/`residential` under 250 m2 and up
// to 13 m); small flats (`apartments` under 600 m2 and up to 20 m). Everything else
// (commercial, industrial, large or tall buildings, building parts, raised parts) is flat.
enum class RoofGroup : uint8_t { Sacred, Houses, Sheds, SmallBlocks, SmallFlats, Flat, Count };
RoofGroup roof_group(const Building& building, double area);

// What the extract's own roof:shape tags say: per group, how many whole ground-standing
// buildings carry one and how many of those are pitched (any shape but flat). Counts: the
// evidence of a farm's tiles, each over its core box, adds up to the region's (docs/farm.md).
struct RoofEvidence {
    int tagged[static_cast<int>(RoofGroup::Count)] = {};
    int pitched[static_cast<int>(RoofGroup::Count)] = {};
};
// The evidence of the buildings `counted` accepts (all when it is empty).
RoofEvidence roof_evidence(const std::vector<Building>& buildings, const BuildingTagIndex& tags,
                           const std::function<bool(const Building&)>& counted = {});

// The share of a group's untagged roofs that are pitched: churches and farm buildings pitched
// unless the extract's tags say otherwise; the other groups flat (the OSM default roof:shape)
// unless the extract's tagged roofs say otherwise: their pitched share, of the group's own tags
// (shrunk by count towards the share of all the homes' and sheds' tags, itself shrunk towards
// flat), so a region of flat roofs keeps them and one of pitched roofs gets them.
double pitched_share(const RoofEvidence& evidence, RoofGroup group);

// The default for untagged roofs (seeded per building): pitched (mostly gabled, some hipped or
// half-hipped; sheds gabled or skillion) with the group's pitched_share, else flat. Also returns
// the pitch in degrees for pitched shapes.
RoofShape default_roof(const Building& building, double area, uint64_t seed, double* pitch_deg,
                       const RoofEvidence& evidence = {});

// roof:shape text -> shape; false for unknown values.
bool parse_roof_shape(const char* text, RoofShape* shape);
// roof:direction: degrees (0 = north, clockwise) or a compass point (N, NNE, ...); false otherwise.
bool parse_compass_direction(const char* text, double* degrees);

// Whether a face is planar, between z_min and z_max and over the footprint (within tolerance).
bool roof_face_is_valid(const RoofFace& face, const Building& building, double z_min, double z_max);

// The report notes that name a roof shape: built as tagged or by default; its faces failed the
// checks; built hipped on a footprint it does not suit. Nullopt where that cannot happen (a
// flat roof has no faces to check, a hipped one is hipped already).
struct RoofShapeNotes {
    ReportReason tagged, by_default;
    std::optional<ReportReason> failed_checks, built_hipped;
};
const RoofShapeNotes& roof_shape_notes(RoofShape shape);

}  // namespace citygen
