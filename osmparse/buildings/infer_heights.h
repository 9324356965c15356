// Stage 3: heights where the map has none. Runs after build_buildings, over all buildings at
// once, because the tagged heights of neighbours are one of the rules.
#pragma once

#include <functional>
#include <set>
#include <string>
#include <vector>

#include "common/scene.h"
#include "osmparse/core/osm_data.h"
#include "osmparse/core/params.h"
#include "common/projection.h"
#include "osmparse/core/report.h"

namespace citygen {

// What the land around a building is used for (OSM landuse=*), as far as heights care.
enum class LandUse : uint8_t { None, Residential, Commercial, Retail, Industrial };

struct LandUseArea {
    Ring outer;               // counter-clockwise or not: only point-in-polygon is asked
    std::vector<Ring> holes;
    LandUse use = LandUse::None;
};

// The landuse=residential|commercial|retail|industrial areas of the map, projected (the same
// OSM areas build_land_cover paints as built-up ground). Areas over kMaxObjectExtent across
// (a stray node) are left out and noted as ReportReason::LandUseTooLarge under
// ReportKind::BuildingHeights.
std::vector<LandUseArea> land_use_areas(const OsmData& osm, const Projection& projection, ParseReport& report);

// What rule 3 and the calibration below read of the extract as a whole, as lists: the evidence of
// the parts of a region (a farm's tiles, each over its core box) concatenated is the region's,
// so every tile can guess as one parse of the region does (docs/farm.md).
struct HeightEvidence {
    static constexpr int kFootprintClasses = 5;   // rule 3's: under 80, 200, 600, 1500 m2, larger
    static constexpr int kCalibratedGroups = 4;   // houses, untyped and workplaces, flats, other types
    struct Tagged {
        std::string type;  // the type rule 3 reads (`building=building` as `yes`)
        int area_class;    // its footprint class, 0 to kFootprintClasses - 1
        double height;
    };
    struct Ratio {
        int group;         // 0 to kCalibratedGroups - 1
        double log_ratio;  // log(tagged height / the group's rule for it)
    };
    std::vector<Tagged> tagged;     // every building whose height its own tags give
    std::vector<Ratio> calibration; // those of them in a calibrated group
};

// The evidence of the tagged buildings among `buildings` that `counted` accepts (all when it is
// empty), read as infer_heights reads them.
HeightEvidence height_evidence(const std::vector<Building>& buildings, const std::vector<LandUseArea>& land_use,
                               const BuildingParams& params, const std::set<OsmRef>& homes = {},
                               const std::function<bool(const Building&)>& counted = {});

// Replaces the random height of every ground-standing building with nothing tagged
// (height_source Random, min_height 0) by the first rule that applies; height_rule records it.
// Every rule reads one type: `building`'s, but `apartments` for the buildings in `homes`
// (homes_by_use) and `residential` for a house type over 1,000 m2 (a block, not a house):
//  1. TypeAndArea for sure things: a footprint under 30 m2, or a garage/shed/carport/kiosk-like
//     type, is a one-storey shed; a house-like type under 1,000 m2 is a two-storey house (a
//     larger one is a block: the rules of `residential`) (both rules first
//     because a neighbour's height says little about a garage beside a tower);
//  1b. TypeAndArea for residential towers, of tower_height: a home (apartments, residential,
//     dormitory) whose plan is deep in every direction in a town of blocks (is_point_block);
//     before the neighbours: a tower among blocks is not their height;
//  1c. Neighbours, a twin (ReportReason::Twin): the nearest tagged building within 60 m of the
//     same type (not `yes`) and a footprint within 10% of its own: an estate built in series from
//     one design; before the towers, whose rule only guesses what a twin knows;
//  2. Neighbours: the distance-weighted median height of the nearest (up to 8) tagged buildings
//     (height or building:levels) within 150 m that are most like it: the same type and a
//     footprint within 3x of its own (at least 2), else the same type when it is not `yes`
//     (at least 2), else such a footprint (at least 3), else any (at least 3: the street's scale);
//     when the chosen group disagrees (its upper quartile over twice its lower: houses beside
//     towers) it says nothing and the later rules decide (it comes back as rule 7);
//  3. Neighbours, extract-wide: the median height of the tagged buildings of the same type and
//     footprint class (under 80, 200, 600, 1500 m2, larger) anywhere in the data (at least 3).
//     The scene format has one value for rules 2 and 3 (a new one would change its schema);
//     the report's notes under ReportKind::BuildingHeights tell them apart;
//  4. TypeAndArea: an untyped building of hall size on industrial or retail land is an
//     industrial or retail hall (the land use of `land_use`, at the footprint's centroid);
//  5. TypeAndArea from the surroundings, for untyped buildings and workplaces (`office`,
//     `commercial`, `civic`, `public`, `government`): levels_from_surroundings of its footprint,
//     the grain of the town around it and whether it shares a wall;
//  6. TypeAndArea: a height by building type (height_by_type_and_area); for homes (apartments,
//     residential, dormitory) as the table gives them, whatever the fabric;
//  7. Neighbours that disagree (rule 2's group): their weighted median;
// The type-and-area rules (1 for houses, 4, 5, 6) are calibrated on the extract's own tagged
// buildings, in four groups (houses, untyped buildings and workplaces, flats, other types): when
// a group has at least 10 tagged buildings, its guesses are multiplied by their median ratio
// tagged height / rule (in logs, shrunk towards 1 by count; noted as ReportReason::Calibrated), so
// a city of five-storey blocks learns its blocks from its tagged ones;
//  8. Random: the seeded random height in [random_min_height, random_max_height] stays (only
//     reached for types the table does not know, with nothing tagged like it).
// Only buildings whose height comes from their own tags are ever used, so a building whose tags
// are hidden (--hide-height-tags) cannot see its own truth (rule 5 reads footprints only). Each
// guess is jittered by up to +-10% (seeded per building) so a street is not one height. The
// pieces of one OSM building (a repaired bow-tie, a multipolygon's outers) get one guess from
// their joint footprint (its area, its area-weighted centroid, a wall shared by any). Levels
// are recomputed from the new height. Counts go to ReportKind::BuildingHeights in the report. The
// result does not depend on the order of `buildings` beyond ties in distance.
// `region`: the evidence rule 3 and the calibration read instead of the extract's own (a farm's,
// gathered over all its tiles); the neighbour rules read the extract around each building.
void infer_heights(std::vector<Building>& buildings, const std::vector<LandUseArea>& land_use,
                   const BuildingParams& params, ParseReport& report, const std::set<OsmRef>& homes = {},
                   const HeightEvidence* region = nullptr);

// Rule 5 alone (exposed for tests): storeys of an untyped building or a workplace with a
// footprint of `area` m2 among buildings whose median footprint within 400 m is `grain` m2;
// `attached` when it shares a wall with another building. The constants and their reasons are
// in infer_heights.cpp.
double levels_from_surroundings(double area, double grain, bool attached);

// Rule 1b alone (exposed for tests): whether a building of `type` whose plan (courtyards left
// out) has `area` m2 and `perimeter` m (holes included) among buildings of median footprint
// `grain` m2 is a point block: a home whose plan depth 2 * area / perimeter is at least 13 m
// (26 m across both ways: flats around a core) and whose plan is at most 2,000 m2 (one core's
// floor), where the grain is at least 200 m2.
bool is_point_block(const std::string& type, double area, double perimeter, double grain);
// How much higher than in a town of blocks (a grain of 200 m2 or finer: 1) homes stand among
// buildings of median footprint `grain` m2: (grain / 200)^0.65, as levels_from_surroundings grows
// with the grain; 1 again over 500 m2 (an estate of halls, no denser city). Towers (tower_height)
// grow with it.
double fabric_factor(double grain);
// The height rule 1b gives a residential tower among buildings of median footprint `grain` m2:
// 15 storeys, more in a fabric of 200-500 m2 (as levels_from_surroundings grows with it; a
// coarser grain is an estate of halls).
double tower_height(double grain, const BuildingParams& params);
// The buildings (not parts) whose use tags say they hold flats while their form
// (building=yes, commercial, office, retail, civic, public, government) says nothing of homes:
// building:use=residential|apartments, tourism=apartment (holiday flats). OSM's building=* is the
// form, these keys the use; infer_heights reads them as `apartments` (`homes`).
std::set<OsmRef> homes_by_use(const OsmData& osm);

// Rule 1, 4 and 6 alone (exposed for tests): the height of a building of `type` with a footprint of
// `area` m2 on land used as `use`, or 0 when the type says nothing; `sure` tells whether the rule
// beats neighbours.
double height_by_type_and_area(const std::string& type, double area, bool* sure, LandUse use = LandUse::None);

}  // namespace citygen
