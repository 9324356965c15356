#include "osmparse/buildings/infer_heights.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>
#include <set>
#include <unordered_map>

#include "common/rng.h"
#include "common/scene_limits.h"
#include "osmparse/polygons/grid_cell_key.h"

namespace citygen {

namespace {

constexpr double kNeighbourRadius = 150;  // metres
constexpr size_t kMaxNeighbours = 8;
constexpr size_t kMinNeighbours = 3;
constexpr double kMaxNeighbourSpread = 2;  // upper over lower quartile of an agreeing group
constexpr double kSimilarArea = 3;        // a neighbour's footprint within this factor is "like" it
constexpr double kLandUseCell = 250;      // metres: grid cell of the land use index
constexpr double kHallArea = 200;         // m2: an untyped building this large on industrial land is a hall
// Tagged buildings of a kind the extract-wide rule needs: a handful (a few tagged garages among
// thousands of untagged `yes` buildings) is no sample of a whole city.
constexpr size_t kMinExtractSamples = 10;
enum Salt : uint64_t { kJitter = 201 };

// Rule 5, storeys from the surroundings: levels = kBaseLevels * (grain / 100 m2)^kGrainExponent
// * (area / grain)^kAreaExponent, times kAttachedFactor for a building that shares a wall, in
// at least 1. The exponents are a least-absolute-error fit (on log storeys) to the tagged
// buildings of two of our extracts, pooled, rounded. kBaseLevels is that fit's own value: a
// prior for cities we do not have is the median of what the cities we hold say, one vote per
// city (tests/bench/height_bench.sh, leave-one-city-out), not a fit to the cities with most
// tags. The extract's own tagged buildings then calibrate it where they can (infer_heights).
// Figures: docs/bench/2026-12-heights.md and docs/bench/2026-11-heights.md.
// Homes (residential, apartments, dormitory) keep the type table: the tagged homes of our
// extracts are mostly towers (mappers tag the notable ones), and a factor fitted to them made
// ordinary blocks of flats far worse.
//  - grain, the median footprint of the buildings within kGrainRadius: the fabric of the town.
//    A suburb or village of houses has a grain of 100-150 m2, a city of blocks of flats 300-400.
//    Denser fabric is built higher: storeys grow about as grain^0.65 (1.6 at 100 m2, 3.5 at 340).
//    A coarser grain than kMaxGrain is an estate of halls (a shopping centre, a campus), not a
//    taller city;
//  - area / grain: within one fabric a footprint ten times the usual is twice as tall
//    (10^0.3 = 2): large footprints are blocks and halls, not towers in proportion; beyond
//    kMaxRelativeArea times the grain a footprint is a hall or a complex of wings, no taller;
//  - untyped buildings and workplaces (office, commercial, civic, public, government) alike;
//  - attached: a building sharing a wall (within kAttachedGap) stands in a closed block or a
//    terrace, built higher than a detached one of the same footprint;
constexpr double kBaseLevels = 1.6;
constexpr double kGrainExponent = 0.65;
constexpr double kAreaExponent = 0.3;
constexpr double kAttachedFactor = 1.35;
constexpr double kMinGrain = 50;           // m2: a yard of sheds is no finer fabric than this
constexpr double kMaxGrain = 500;          // m2
constexpr double kMaxRelativeArea = 10;
constexpr double kGrainRadius = 400;       // metres: a town quarter
constexpr double kAttachedGap = 0.5;       // metres

// Residential towers, rule 1b. 15 storeys (kTowerLevels) is a common residential high-rise.
// In a fabric denser than kPointBlockMinGrain a tower stands higher, as the rest of the town does
// (levels_from_surroundings: storeys grow as grain^kGrainExponent, no constant of its own), as
// the tagged towers of a dense city do. Never lower than kTowerLevels: towers in a town of
// houses are high-rises too; and no higher in an estate of halls (a grain over kMaxGrain: a
// campus, not a denser city). Not fitted to one city: our extracts ask for different storeys
// per tower (docs/bench/2026-11-heights.md).
constexpr double kTowerLevels = 15;
// Point blocks: a home whose plan is deep in every direction is a residential tower. A flat is
// daylit from one facade to about 12-13 m deep, so a slab of flats (blocks, terraces)
// is at most two such depths across: its plan depth 2 * area / perimeter (half the side of a
// square, the width of a long strip) stays under 13 m. A plan at least 26 m across both ways
// (kPointBlockDepth) puts flats around a central core of lifts and stairs, and a core only pays
// for itself on a tall building. The tagged homes this deep in our extracts are all tall
// (docs/bench/2026-11-heights.md).
constexpr double kPointBlockDepth = 13;    // metres
// One core of lifts and stairs serves a floor of about 2,000 m2 at most (residential towers'
// floors are 600-1,500 m2): a deep plan larger than kMaxPointBlockArea is a block of several
// cores, mid-rise (a mansion block, a terrace of flats).
constexpr double kMaxPointBlockArea = 2000;  // m2
// In a village fabric (houses, grain under kPointBlockMinGrain) a deep home is a farmstead or a
// care home, not a tower.
constexpr double kPointBlockMinGrain = 200;  // m2
// Twins: an estate is built in series from one design (rows of identical slabs, pairs of towers,
// a terrace of one builder's houses): a building of the same type and footprint, within
// kTwinArea, standing within kTwinDistance has the same storeys. The nearest such tagged one
// says more about it than any rule of type, footprint or fabric (pairs of towers, rows of
// blocks of flats; docs/bench/2026-11-heights.md).
constexpr double kTwinDistance = 60;       // metres between centroids: the next building or the one after
constexpr double kTwinArea = 1.1;
// A house has a house-sized footprint: a "terrace" or "house" over kMaxHouseArea is a block
// (mappers tag whole blocks of flats terrace) and gets the rules of a building of flats instead
// of the two-storey house rule.
constexpr double kMaxHouseArea = 1000;     // m2: ten row houses of 100 m2

// The type-and-area rules whose storeys differ between regions, calibrated as a group: houses
// (the two-storey rule), the fabric rule (5: untyped buildings and workplaces), flats (the type
// table's homes) and the other types of the table (halls, schools, churches...). Sheds and
// towers are not calibrated: a shed is one storey everywhere, and the few tagged towers of a
// city are the notable ones.
enum PriorGroup { kHouses, kFabric, kFlats, kOtherTypes, kPriorGroups, kNotCalibrated = kPriorGroups };
static_assert(kPriorGroups == HeightEvidence::kCalibratedGroups);
// The extract's own tagged buildings calibrate a group when there are at least kMinCalibration of
// it: its median ratio tagged / prior, in logs, shrunk towards the prior as n / (n + kCalibrationWeight)
// (at kCalibrationWeight tagged buildings the extract and the prior count alike). A handful of
// tagged buildings are the notable ones of a city (towers, churches), no sample of its blocks.
constexpr size_t kMinCalibration = 10;
constexpr double kCalibrationWeight = 10;

bool is_one_of(const std::string& value, std::initializer_list<const char*> list) {
    for (const char* s : list)
        if (value == s) return true;
    return false;
}

// Types that say nothing about the building beyond "it is one".
bool is_untyped(const std::string& type) { return is_one_of(type, {"yes", "building", ""}); }

// `building=building` is a common spelling of `yes`: one key for both.
const std::string& type_key(const std::string& type) {
    static const std::string yes = "yes";
    return is_untyped(type) ? yes : type;
}

// Footprint classes for the extract-wide rule: the same bounds as the area table below.
int area_class(double area) {
    static_assert(HeightEvidence::kFootprintClasses == 5);
    if (area < 80) return 0;
    if (area < 200) return 1;
    if (area < 600) return 2;
    return area < 1500 ? 3 : 4;
}

bool similar_area(double a, double b) { return a <= kSimilarArea * b && b <= kSimilarArea * a; }

struct Tagged {
    Vec2 at;
    double height;
    double area;
    const std::string* type;
};

// Centroids of tagged buildings in square cells of the neighbour radius.
class TaggedGrid {
public:
    explicit TaggedGrid(std::vector<Tagged> items) : items_(std::move(items)) {
        for (size_t i = 0; i < items_.size(); ++i) cells_[grid_cell_key(cell(items_[i].at.x), cell(items_[i].at.y))].push_back(i);
    }
    // All within the radius, nearest first (ties by index: deterministic).
    std::vector<std::pair<double, size_t>> nearest(Vec2 p) const {
        std::vector<std::pair<double, size_t>> found;
        const int64_t cx = cell(p.x), cy = cell(p.y);
        for (int64_t dx = -1; dx <= 1; ++dx)
            for (int64_t dy = -1; dy <= 1; ++dy) {
                auto it = cells_.find(grid_cell_key(cx + dx, cy + dy));
                if (it == cells_.end()) continue;
                for (size_t i : it->second) {
                    const double d = length(items_[i].at - p);
                    if (d <= kNeighbourRadius) found.push_back({d, i});
                }
            }
        std::sort(found.begin(), found.end());
        return found;
    }
    const Tagged& operator[](size_t i) const { return items_[i]; }
    size_t size() const { return items_.size(); }

private:
    static int64_t cell(double v) { return static_cast<int64_t>(std::floor(v / kNeighbourRadius)); }
    std::vector<Tagged> items_;
    std::unordered_map<int64_t, std::vector<size_t>> cells_;
};

// Weighted median: the value where the weights on each side balance (nearer counts more).
double weighted_median(std::vector<std::pair<double, double>> values) {  // (value, weight)
    std::sort(values.begin(), values.end());
    double total = 0;
    for (const auto& v : values) total += v.second;
    double run = 0;
    for (const auto& v : values) {
        run += v.second;
        if (run >= 0.5 * total) return v.first;
    }
    return values.back().first;
}

double median(std::vector<double> values) {
    std::sort(values.begin(), values.end());
    const size_t n = values.size();
    return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

Vec2 centroid(const Ring& ring) {
    Vec2 c{0, 0};
    for (Vec2 p : ring) c = c + p;
    return ring.empty() ? c : c * (1.0 / ring.size());
}

// Workplaces whose height follows the fabric of their town like an untyped building's: a town
// hall or an office in a village has two storeys, in a city six.
bool is_workplace(const std::string& type) {
    return is_one_of(type, {"office", "commercial", "civic", "public", "government"});
}

bool is_home(const std::string& type) { return is_one_of(type, {"apartments", "residential", "dormitory"}); }

bool is_house(const std::string& type) {
    return is_one_of(type, {"house", "detached", "semidetached_house", "terrace", "bungalow", "villa"});
}

double perimeter(const Ring& ring) {
    double sum = 0;
    for (size_t k = 0; k < ring.size(); ++k) sum += length(ring[(k + 1) % ring.size()] - ring[k]);
    return sum;
}

// Rule 5's inputs: the grain around a building and whether it shares a wall. Footprints only,
// never heights, so no building's hidden truth can reach its guess.
class Surroundings {
public:
    explicit Surroundings(const std::vector<Building>& buildings) : buildings_(buildings) {
        for (size_t i = 0; i < buildings.size(); ++i) {
            const Building& b = buildings[i];
            boxes_.push_back(bounds_of(b.outer));
            if (b.outer.size() < 3) continue;
            const Box2& box = boxes_.back();
            for (int64_t x = cell(box.min.x - kAttachedGap, kWallCell); x <= cell(box.max.x + kAttachedGap, kWallCell); ++x)
                for (int64_t y = cell(box.min.y - kAttachedGap, kWallCell); y <= cell(box.max.y + kAttachedGap, kWallCell); ++y)
                    walls_[grid_cell_key(x, y)].push_back(i);
            if (b.is_part) continue;  // parts are pieces of a building, not buildings of the town
            const Vec2 c = centroid(b.outer);
            grain_cells_[grid_cell_key(cell(c.x, kGrainCell), cell(c.y, kGrainCell))].push_back(
                {c, std::fabs(signed_area(b.outer))});
        }
    }
    // Median footprint (the upper one of an even count) of the buildings within kGrainRadius of
    // the centre of the kGrainCell square holding p: the grain is a property of the quarter, and
    // one median per square instead of per building keeps this stage fast (a city centre has
    // thousands of buildings within kGrainRadius).
    double grain(Vec2 p) const {
        const int64_t cx = cell(p.x, kGrainCell), cy = cell(p.y, kGrainCell);
        auto [known, inserted] = grain_of_square_.try_emplace(grid_cell_key(cx, cy), 0.0);
        if (!inserted) return known->second;
        const Vec2 centre{(cx + 0.5) * kGrainCell, (cy + 0.5) * kGrainCell};
        std::vector<double>& areas = scratch_;
        areas.clear();
        const int64_t reach = static_cast<int64_t>(std::ceil(kGrainRadius / kGrainCell));
        for (int64_t dx = -reach; dx <= reach; ++dx)
            for (int64_t dy = -reach; dy <= reach; ++dy) {
                auto it = grain_cells_.find(grid_cell_key(cx + dx, cy + dy));
                if (it == grain_cells_.end()) continue;
                for (const auto& [at, area] : it->second)
                    if (length(at - centre) <= kGrainRadius) areas.push_back(area);
            }
        if (areas.empty()) return 0;
        std::nth_element(areas.begin(), areas.begin() + areas.size() / 2, areas.end());
        return known->second = areas[areas.size() / 2];
    }
    // Whether building i shares a wall with another building (of its own kind: parts with parts;
    // not another piece of the same OSM building).
    bool attached(size_t i) const {
        const Building& b = buildings_[i];
        const Box2& box = boxes_[i];
        for (int64_t x = cell(box.min.x, kWallCell); x <= cell(box.max.x, kWallCell); ++x)
            for (int64_t y = cell(box.min.y, kWallCell); y <= cell(box.max.y, kWallCell); ++y) {
                auto it = walls_.find(grid_cell_key(x, y));
                if (it == walls_.end()) continue;
                for (size_t j : it->second) {
                    if (j == i || buildings_[j].is_part != b.is_part || buildings_[j].osm == b.osm) continue;
                    Box2 grown = boxes_[j];
                    grown.extend(grown.min - Vec2(kAttachedGap, kAttachedGap));
                    grown.extend(grown.max + Vec2(kAttachedGap, kAttachedGap));
                    if (grown.overlaps(box) && rings_within(b.outer, buildings_[j].outer, kAttachedGap)) return true;
                }
            }
        return false;
    }

private:
    static constexpr double kGrainCell = 100, kWallCell = 50;
    static int64_t cell(double v, double size) { return static_cast<int64_t>(std::floor(v / size)); }
    static double point_segment_distance(Vec2 p, Vec2 a, Vec2 b) {
        const Vec2 d = b - a;
        const double len2 = dot(d, d);
        const double t = len2 > 0 ? std::clamp(dot(p - a, d) / len2, 0.0, 1.0) : 0.0;
        return length(p - (a + d * t));
    }
    // Some vertex of one ring within `gap` of an edge of the other.
    static bool rings_within(const Ring& r, const Ring& s, double gap) {
        for (int pass = 0; pass < 2; ++pass) {
            const Ring& from = pass ? s : r;
            const Ring& to = pass ? r : s;
            for (Vec2 p : from)
                for (size_t k = 0; k < to.size(); ++k)
                    if (point_segment_distance(p, to[k], to[(k + 1) % to.size()]) < gap) return true;
        }
        return false;
    }
    const std::vector<Building>& buildings_;
    std::vector<Box2> boxes_;
    std::unordered_map<int64_t, std::vector<size_t>> walls_;
    std::unordered_map<int64_t, std::vector<std::pair<Vec2, double>>> grain_cells_;
    // The grains asked for so far (not thread-safe: one guesser runs on one thread).
    mutable std::unordered_map<int64_t, double> grain_of_square_;
    mutable std::vector<double> scratch_;
};

// Rule 1c: a tagged twin, or 0: the nearest tagged building within kTwinDistance of the same
// type whose footprint is within kTwinArea of its own; `near` is grid.nearest of its centroid.
// Asked for typed buildings only (`yes` is no type: two untyped buildings of one size are no estate).
double twin_height(const TaggedGrid& grid, const std::vector<std::pair<double, size_t>>& near, const std::string& type,
                   double area) {
    for (const auto& [d, i] : near) {
        if (d > kTwinDistance) break;
        const Tagged& t = grid[i];
        if (type_key(*t.type) == type_key(type) && t.area <= kTwinArea * area && area <= kTwinArea * t.area)
            return t.height;
    }
    return 0;
}

// Rule 2: the like tagged buildings nearby, or 0 when there are too few or they disagree (then
// `disagreeing` gets their weighted median: still better than a random height).
double height_from_neighbours(const TaggedGrid& grid, const std::vector<std::pair<double, size_t>>& near,
                              const std::string& type, double area, double* disagreeing) {
    // (height, weight) of the nearest up to kMaxNeighbours in each group, from most to least alike.
    std::vector<std::pair<double, double>> same_both, same_type, same_size, any;
    auto add = [](std::vector<std::pair<double, double>>& group, double height, double weight) {
        if (group.size() < kMaxNeighbours) group.push_back({height, weight});
    };
    for (const auto& [d, i] : near) {
        const double w = 1 / (d + 20), h = grid[i].height;
        const bool type_alike = type_key(*grid[i].type) == type_key(type);
        const bool size_alike = similar_area(grid[i].area, area);
        add(any, h, w);
        if (type_alike) add(same_type, h, w);
        if (size_alike) add(same_size, h, w);
        if (type_alike && size_alike) add(same_both, h, w);
    }
    // Two of the same type say something; a mixed group needs three. A group that disagrees
    // (its upper quartile over twice its lower: houses beside towers) says nothing about one
    // more building; the footprint rules decide then. Both chosen on the half-hidden splits of
    // tests/bench/height_bench.sh (docs/bench/2026-11-heights.md).
    auto agreed = [&](const std::vector<std::pair<double, double>>& group) {
        std::vector<double> h;
        for (const auto& v : group) h.push_back(v.first);
        std::sort(h.begin(), h.end());
        if (h[3 * h.size() / 4] <= kMaxNeighbourSpread * h[h.size() / 4]) return weighted_median(group);
        *disagreeing = weighted_median(group);
        return 0.0;
    };
    if (same_both.size() >= 2) return agreed(same_both);
    // (`yes` is no type: two untyped buildings of any size are not alike.)
    if (same_type.size() >= 2 && !is_untyped(type)) return agreed(same_type);
    for (const auto* group : {&same_size, &any})
        if (group->size() >= kMinNeighbours) return agreed(*group);
    return 0;
}

// Land use lookup: each area in the grid cells its bounding box touches.
class LandUseIndex {
public:
    explicit LandUseIndex(const std::vector<LandUseArea>& areas) : areas_(areas) {
        for (size_t i = 0; i < areas.size(); ++i) {
            Box2 box;
            for (Vec2 p : areas[i].outer) box.extend(p);
            if (box.empty()) continue;
            for (int64_t x = cell(box.min.x); x <= cell(box.max.x); ++x)
                for (int64_t y = cell(box.min.y); y <= cell(box.max.y); ++y) cells_[{x, y}].push_back(i);
        }
    }
    // The use of the first area (in map order) holding p; industrial and retail win over the
    // others where areas overlap, as a hall inside a residential area is still a hall.
    LandUse at(Vec2 p) const {
        auto it = cells_.find({cell(p.x), cell(p.y)});
        if (it == cells_.end()) return LandUse::None;
        LandUse found = LandUse::None;
        for (size_t i : it->second) {
            const LandUseArea& a = areas_[i];
            if (!point_in_ring(p, a.outer)) continue;
            bool in_hole = false;
            for (const Ring& h : a.holes) in_hole = in_hole || point_in_ring(p, h);
            if (in_hole) continue;
            if (a.use == LandUse::Industrial || a.use == LandUse::Retail) return a.use;
            if (found == LandUse::None) found = a.use;
        }
        return found;
    }

private:
    static int64_t cell(double v) { return static_cast<int64_t>(std::floor(v / kLandUseCell)); }
    const std::vector<LandUseArea>& areas_;
    std::map<std::pair<int64_t, int64_t>, std::vector<size_t>> cells_;
};

}  // namespace

std::vector<LandUseArea> land_use_areas(const OsmData& osm, const Projection& projection, ParseReport& report) {
    std::vector<LandUseArea> out;
    for (const OsmArea& area : osm.land_cover_areas) {
        const char* landuse = area.tags.get("landuse");
        if (!landuse) continue;
        const std::string value = landuse;
        LandUse use = value == "residential" ? LandUse::Residential
                      : value == "commercial" ? LandUse::Commercial
                      : value == "retail"     ? LandUse::Retail
                      : value == "industrial" ? LandUse::Industrial
                                              : LandUse::None;
        if (use == LandUse::None) continue;
        auto project = [&](const std::vector<LatLon>& points) {
            Ring ring;
            for (const LatLon& p : points) ring.push_back(projection.to_local(p.lat, p.lon));
            return ring;
        };
        for (const OsmPolygon& polygon : area.polygons) {
            LandUseArea a;
            a.outer = project(polygon.outer);
            for (const auto& inner : polygon.inners) a.holes.push_back(project(inner));
            a.use = use;
            if (a.outer.size() < 3) continue;
            // The lookup grid holds every cell of an area's box: one stray node must not make
            // that millions of cells. No real land use area is this large.
            Box2 box;
            for (Vec2 p : a.outer) box.extend(p);
            if (std::max(box.max.x - box.min.x, box.max.y - box.min.y) > kMaxObjectExtent) {
                report.note(ReportKind::BuildingHeights, ReportReason::LandUseTooLarge);
                continue;
            }
            out.push_back(std::move(a));
        }
    }
    return out;
}

double levels_from_surroundings(double area, double grain, bool attached) {
    grain = std::clamp(grain, kMinGrain, kMaxGrain);
    double levels = kBaseLevels * std::pow(grain / 100, kGrainExponent) *
                    std::pow(std::min(area / grain, kMaxRelativeArea), kAreaExponent);
    if (attached) levels *= kAttachedFactor;
    return std::max(levels, 1.0);
}

bool is_point_block(const std::string& type, double area, double perimeter, double grain) {
    return is_home(type) && perimeter > 0 && 2 * area / perimeter >= kPointBlockDepth && area <= kMaxPointBlockArea &&
           grain >= kPointBlockMinGrain;
}

double fabric_factor(double grain) {
    // A grain coarser than kMaxGrain is an estate of halls (a campus, industry), no denser city.
    const double denser = grain > kMaxGrain ? 1.0 : std::max(grain / kPointBlockMinGrain, 1.0);
    return std::pow(denser, kGrainExponent);
}

double tower_height(double grain, const BuildingParams& params) {
    return kTowerLevels * fabric_factor(grain) * params.level_height;
}

std::set<OsmRef> homes_by_use(const OsmData& osm) {
    std::set<OsmRef> out;
    for (const OsmArea& area : osm.building_areas) {
        const char* building = area.tags.get("building");
        if (!building) continue;
        const std::string form = building;
        if (!is_untyped(form) && !is_workplace(form) && form != "retail") continue;
        const char* use = area.tags.get("building:use");
        const char* tourism = area.tags.get("tourism");
        if ((use && is_one_of(use, {"residential", "apartments"})) || (tourism && is_one_of(tourism, {"apartment", "apartments"})))
            out.insert(area.ref);
    }
    return out;
}

double height_by_type_and_area(const std::string& type, double area, bool* sure, LandUse use) {
    *sure = true;
    if (area > kMaxHouseArea && is_house(type))
        return height_by_type_and_area("residential", area, sure, use);
    if (area < 30 || is_one_of(type, {"garage", "garages", "carport", "shed", "kiosk", "hut", "toilets",
                                      "transformer_tower", "service", "greenhouse", "cabin"}))
        return 3;
    if (is_house(type)) return type == "bungalow" ? 5 : 8;
    if (is_one_of(type, {"farm_auxiliary", "barn", "stable", "cowshed", "farm"})) return 7;
    *sure = false;
    // An untyped building on industrial or retail land is most likely a hall (a house-sized one
    // is an office or a shop, left to the area rule).
    if (is_untyped(type) && area >= kHallArea) {
        if (use == LandUse::Industrial) return height_by_type_and_area("industrial", area, sure);
        if (use == LandUse::Retail) return height_by_type_and_area("retail", area, sure);
    }
    if (is_one_of(type, {"church", "cathedral"})) return 18;
    if (type == "chapel") return 8;
    if (is_one_of(type, {"apartments", "dormitory"})) return area < 800 ? 15 : 24;
    if (is_one_of(type, {"office", "hotel", "hospital"})) return 18;
    if (is_one_of(type, {"commercial", "civic", "public", "government"})) return 12;
    if (is_one_of(type, {"school", "university", "college", "kindergarten"})) return type == "kindergarten" ? 5 : 10;
    // One storey: so are the retail buildings tagged with levels in our extracts.
    if (is_one_of(type, {"retail", "supermarket"})) return 3;
    if (is_one_of(type, {"industrial", "warehouse", "manufacture", "hangar"})) return 8;
    if (is_untyped(type) || type == "residential") {
        if (area < 80) return 4;
        if (area < 200) return 7;
        if (area < 600) return 10;
        return area < 1500 ? 15 : 21;  // large footprints in towns are blocks of flats or offices
    }
    return 0;
}

namespace {

// The type-and-area rules (1, 1b, 4, 5, 6) for one building, before any neighbour is asked: its
// prior, in the group that calibrates it.
struct TypePrior {
    double height = 0;
    int group = kNotCalibrated;
    bool sure = false, tower = false;
    ReportReason note = ReportReason::FromTypeAndArea;
};

// The plan of one building or of the pieces of one: its footprint area, its area and perimeter
// without the courtyards, where it stands and whether it touches a neighbour.
struct Plan {
    double area = 0, plan_area = 0, plan_perimeter = 0;
    Vec2 at{0, 0};
    bool attached = false;
};

// The height rules for untagged buildings over one extract: what they read of its tagged
// buildings (by type and size, near each building, its own storeys) and its land use.
class HeightGuesser {
public:
    HeightGuesser(const std::vector<Building>& buildings, const std::vector<LandUseArea>& land_use,
                  const BuildingParams& params, const std::set<OsmRef>& homes)
        : buildings_(buildings), params_(params), homes_(homes), uses_(land_use), surroundings_(buildings),
          grid_(tagged_heights()) {}

    // What rule 3 and the calibration read of the buildings `counted` accepts (all when empty).
    HeightEvidence evidence(const std::function<bool(const Building&)>& counted) const;
    // Rule 3's medians and the groups' calibration from `evidence` (the extract's own, or a region's).
    void read(const HeightEvidence& evidence);

    // Guesses the height of one OSM building from its pieces (a repaired bow-tie, a
    // multipolygon's outers are one building: one guess from their joint footprint), in `out`:
    // the buildings the guesser was made with.
    void guess(const std::vector<size_t>& indices, std::vector<Building>& out, ParseReport& report) const;

private:
    // The type every rule reads: a home by its use tags holds flats whatever its form; a house
    // type on a block's footprint (over kMaxHouseArea) is a block of flats.
    const std::string& type_of(const Building& b, double area) const {
        static const std::string apartments = "apartments", residential = "residential";
        if (homes_.count(b.osm)) return apartments;
        return area > kMaxHouseArea && is_house(b.type) ? residential : b.type;
    }
    std::vector<Tagged> tagged_heights() const {
        std::vector<Tagged> tagged;
        for (const Building& b : buildings_)
            if (is_tagged(b))
                tagged.push_back({centroid(b.outer), b.height, std::fabs(signed_area(b.outer)),
                                  &type_of(b, std::fabs(signed_area(b.outer)))});
        return tagged;
    }
    // Whether a building's own tags give its height (never a guess, never a raised part's).
    static bool is_tagged(const Building& b) {
        return b.height_source != HeightSource::Random && b.min_height == 0 && !b.is_part;
    }
    double extract_median(const std::string& type, double area) const {
        auto it = kind_median_.find({type_key(type), area_class(area)});
        // An untyped building's size says more than the whole extract's `yes` buildings do.
        if (it == kind_median_.end() && !is_untyped(type)) it = kind_median_.find({type_key(type), -1});
        return it == kind_median_.end() ? 0.0 : it->second;
    }
    TypePrior type_prior(const std::string& type, const Plan& plan) const;
    Plan plan_of(const std::vector<size_t>& indices) const;

    const std::vector<Building>& buildings_;
    const BuildingParams& params_;
    const std::set<OsmRef>& homes_;
    LandUseIndex uses_;
    Surroundings surroundings_;
    TaggedGrid grid_;
    // Rule 3's medians: key (type, footprint class) for the type and footprint class, (type, -1)
    // for the type alone.
    std::map<std::pair<std::string, int>, double> kind_median_;
    std::vector<double> calibration_ = std::vector<double>(kPriorGroups + 1, 1.0);
};

TypePrior HeightGuesser::type_prior(const std::string& type, const Plan& plan) const {
    TypePrior p;
    const double area = plan.area;
    const Vec2 at = plan.at;
    // Only untyped halls ask the land use (the lookup is most of this stage's time).
    const LandUse use = is_untyped(type) && area >= kHallArea ? uses_.at(at) : LandUse::None;
    const double by_type = height_by_type_and_area(type, area, &p.sure, use);
    bool ignored = false;
    const bool hall_by_land_use = by_type > 0 && by_type != height_by_type_and_area(type, area, &ignored);
    if (p.sure) {
        p.height = by_type;
        if (is_house(type)) p.group = kHouses;
    } else if (is_point_block(type, plan.plan_area, plan.plan_perimeter, surroundings_.grain(at))) {
        p.height = tower_height(surroundings_.grain(at), params_);
        p.tower = true;
        p.note = ReportReason::PointBlock;
    } else if (hall_by_land_use) {
        p.height = by_type;
        p.group = kOtherTypes;
        p.note = ReportReason::FromTypeAreaAndLandUse;
    } else if (is_untyped(type) || is_workplace(type)) {
        p.height = params_.level_height * levels_from_surroundings(area, surroundings_.grain(at), plan.attached);
        p.group = kFabric;
        p.note = ReportReason::FromSurroundings;
    } else if (by_type > 0) {
        // Flats: the table's storeys in any fabric. Dense towns differ: Monaco's flats stand
        // twice the table, Malta's two thirds of it (docs/bench/2026-12-heights.md).
        p.height = by_type;
        p.group = is_home(type) ? kFlats : kOtherTypes;
    }
    return p;
}

// The tagged buildings' heights by type and footprint class (rule 3), and the extract's own
// storeys: each group's prior against the tagged buildings of it (their own footprints, as one of
// them would be guessed with its tags hidden).
HeightEvidence HeightGuesser::evidence(const std::function<bool(const Building&)>& counted) const {
    HeightEvidence e;
    for (size_t i = 0; i < buildings_.size(); ++i) {
        const Building& b = buildings_[i];
        if (!is_tagged(b) || (counted && !counted(b))) continue;
        Plan plan;
        plan.area = std::fabs(signed_area(b.outer));
        plan.plan_area = plan.area;
        plan.plan_perimeter = perimeter(b.outer);
        for (const Ring& hole : b.holes) {
            plan.plan_area -= std::fabs(signed_area(hole));
            plan.plan_perimeter += perimeter(hole);
        }
        plan.at = centroid(b.outer);
        plan.attached = surroundings_.attached(i);
        const std::string& type = type_of(b, plan.area);
        e.tagged.push_back({type_key(type), area_class(plan.area), b.height});
        const TypePrior p = type_prior(type, plan);
        // Finite: a tagged height of 1e-320 m would make the ratio's log -inf.
        const double log_ratio = p.height > 0 ? std::log(b.height / p.height) : 0;
        if (p.group != kNotCalibrated && p.height > 0 && std::isfinite(log_ratio))
            e.calibration.push_back({p.group, log_ratio});
    }
    return e;
}

void HeightGuesser::read(const HeightEvidence& evidence) {
    std::map<std::pair<std::string, int>, std::vector<double>> by_kind;
    for (const HeightEvidence::Tagged& t : evidence.tagged) {
        by_kind[{t.type, t.area_class}].push_back(t.height);
        by_kind[{t.type, -1}].push_back(t.height);
    }
    for (const auto& [kind, heights] : by_kind)
        if (heights.size() >= kMinExtractSamples) kind_median_[kind] = median(heights);
    std::vector<std::vector<double>> ratios(kPriorGroups);
    for (const HeightEvidence::Ratio& r : evidence.calibration) ratios[static_cast<size_t>(r.group)].push_back(r.log_ratio);
    for (int g = 0; g < kPriorGroups; ++g) {
        const double n = static_cast<double>(ratios[g].size());
        if (ratios[g].size() >= kMinCalibration)
            calibration_[g] = std::exp(n / (n + kCalibrationWeight) * median(ratios[g]));
    }
}

Plan HeightGuesser::plan_of(const std::vector<size_t>& indices) const {
    Plan plan;  // plan: courtyards left out
    for (size_t i : indices) {
        const double a = std::fabs(signed_area(buildings_[i].outer));
        plan.area += a;
        plan.at = plan.at + centroid(buildings_[i].outer) * a;
        plan.attached = plan.attached || surroundings_.attached(i);
        plan.plan_area += a;
        plan.plan_perimeter += perimeter(buildings_[i].outer);
        for (const Ring& hole : buildings_[i].holes) {
            plan.plan_area -= std::fabs(signed_area(hole));
            plan.plan_perimeter += perimeter(hole);
        }
    }
    plan.at = plan.area > 0 ? plan.at * (1 / plan.area) : centroid(buildings_[indices[0]].outer);
    return plan;
}

void HeightGuesser::guess(const std::vector<size_t>& indices, std::vector<Building>& out, ParseReport& report) const {
    const Plan plan = plan_of(indices);
    const double area = plan.area;
    const Building& b = buildings_[indices[0]];  // the pieces share their tags
    const std::string& type = type_of(b, area);
    HeightRule rule = HeightRule::Random;
    const TypePrior prior = type_prior(type, plan);
    double height = 0, disagreeing = 0;
    // The tagged buildings within the neighbour radius, nearest first: asked once, by the first
    // rule that needs them.
    std::optional<std::vector<std::pair<double, size_t>>> near;
    auto nearby = [&]() -> const std::vector<std::pair<double, size_t>>& {
        if (!near) near = grid_.nearest(plan.at);
        return *near;
    };
    const TaggedGrid& grid = grid_;
    ReportReason note = prior.note;
    if (prior.sure) {
        height = prior.height * calibration_[prior.group];
        rule = HeightRule::TypeAndArea;
    } else if (!is_untyped(type) && (height = twin_height(grid, nearby(), type, area)) > 0) {
        rule = HeightRule::Neighbours;
        note = ReportReason::Twin;
    } else if (prior.tower) {
        // Before the neighbours: a tower says more about itself than the blocks around it.
        height = prior.height;
        rule = HeightRule::TypeAndArea;
    } else if ((height = height_from_neighbours(grid, nearby(), type, area, &disagreeing)) > 0) {
        rule = HeightRule::Neighbours;
        note = ReportReason::FromTaggedNeighbours;
    } else if ((height = extract_median(type, area)) > 0) {
        rule = HeightRule::Neighbours;
        note = ReportReason::FromExtractMedian;
    } else if (prior.height > 0) {
        height = prior.height * calibration_[prior.group];
        rule = HeightRule::TypeAndArea;
    } else if ((height = disagreeing) > 0) {
        rule = HeightRule::Neighbours;
        note = ReportReason::FromDisagreeingNeighbours;
    }
    if (rule == HeightRule::TypeAndArea && calibration_[prior.group] != 1.0)
        for (size_t n = indices.size(); n > 0; --n) report.note(ReportKind::BuildingHeights, ReportReason::Calibrated);
    if (rule == HeightRule::Random) {
        for (size_t n = indices.size(); n > 0; --n)
            report.note(ReportKind::BuildingHeights, ReportReason::NoHeightRule);
        return;
    }
    const double u = hash_to_unit(hash_keys(params_.seed, static_cast<uint64_t>(b.osm.type),
                                            static_cast<uint64_t>(b.osm.id), kJitter));
    const double jittered = std::clamp(height * (0.9 + 0.2 * u), 2.5, params_.max_height);
    for (size_t i : indices) {
        out[i].height = jittered;
        out[i].height_rule = rule;
        out[i].levels = std::max(1, static_cast<int>(std::lround(jittered / params_.level_height)));
        report.note(ReportKind::BuildingHeights, note);
    }
}

}  // namespace

HeightEvidence height_evidence(const std::vector<Building>& buildings, const std::vector<LandUseArea>& land_use,
                               const BuildingParams& params, const std::set<OsmRef>& homes,
                               const std::function<bool(const Building&)>& counted) {
    return HeightGuesser(buildings, land_use, params, homes).evidence(counted);
}

void infer_heights(std::vector<Building>& buildings, const std::vector<LandUseArea>& land_use,
                   const BuildingParams& params, ParseReport& report, const std::set<OsmRef>& homes,
                   const HeightEvidence* region) {
    HeightGuesser guesser(buildings, land_use, params, homes);
    guesser.read(region ? *region : guesser.evidence({}));
    // The pieces of one OSM building are guessed together.
    std::map<std::pair<OsmRef, bool>, std::vector<size_t>> pieces;
    for (size_t i = 0; i < buildings.size(); ++i) {
        Building& b = buildings[i];
        if (b.height_source == HeightSource::Tagged) b.height_rule = HeightRule::Tagged;
        if (b.height_source == HeightSource::Levels) b.height_rule = HeightRule::Levels;
        if (b.height_source != HeightSource::Random) continue;
        b.height_rule = HeightRule::Random;
        if (b.min_height > 0) continue;  // a raised part: building_heights gave it a storey
        pieces[{b.osm, b.is_part}].push_back(i);
    }
    for (const auto& [ref, indices] : pieces) guesser.guess(indices, buildings, report);
}

}  // namespace citygen
