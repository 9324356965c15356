#include "osmparse/map/place_trees.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

#include "common/rng.h"
#include "common/scene_limits.h"
#include "osmparse/buildings/build_buildings.h"
#include "osmparse/core/osm_units.h"
#include "osmparse/map/place_lamps.h"
#include "osmparse/map/point_placement.h"
#include "osmparse/polygons/clean_footprint.h"
#include "osmparse/polygons/polygon_overlap.h"
#include "osmparse/read/read_osm.h"

namespace citygen {

namespace {

constexpr double kMinHeight = 1, kMaxTreeHeight = 80, kMinCrown = 0.5, kMaxCrown = 40;
constexpr double kTrunkClearance = 0.75;  // metres a trunk keeps from roads and buildings

// The height tags, in the order they are read, with the note that counts each when unusable.
struct HeightTag {
    const char* key;
    ReportReason unusable;
};
constexpr HeightTag kHeightTags[] = {{"height", ReportReason::TreeHeightUnusable},
                                     {"est_height", ReportReason::TreeEstHeightUnusable}};

}  // namespace

Tree tree_from_tags(const OsmTags& tags, ParseReport& report, ReportKind kind) {
    Tree t;
    const char* leaf = tags.get("leaf_type");
    t.leaf_type = leaf && !std::strcmp(leaf, "needleleaved") ? LeafType::Needleleaved : LeafType::Broadleaved;
    const bool needle = t.leaf_type == LeafType::Needleleaved;
    t.height = needle ? 14 : 10;
    t.crown_diameter = needle ? 5 : 7;
    for (const HeightTag& tag : kHeightTags) {
        const char* text = tags.get(tag.key);
        if (!text) continue;
        const std::optional<double> h = parse_osm_length(text);
        if (h && *h >= kMinHeight && *h <= kMaxTreeHeight) {
            t.height = *h;
            break;
        }
        report.note(kind, tag.unusable);
    }
    if (const char* text = tags.get("diameter_crown")) {
        const std::optional<double> d = parse_osm_length(text);
        if (d && *d >= kMinCrown && *d <= kMaxCrown) t.crown_diameter = *d;
        else report.note(kind, ReportReason::CrownDiameterUnusable);
    }
    // A crown wider than the tree is tall reads as a bush: keep it in proportion.
    t.crown_diameter = std::min(t.crown_diameter, 1.2 * t.height);
    return t;
}

namespace {

// Where a trunk may stand: off roads and buildings by kTrunkClearance, off paths, out of water.
class TreeGround {
public:
    explicit TreeGround(const Scene& scene)
        : buildings_(scene.buildings),
          surface_(surface_polygons(scene.roads, scene.joints)),
          paths_(surface_polygons(scene.paths, scene.path_joints)),  // paths, rails, joints
          water_(water_pieces(scene), 200) {}

    const Ring* surface_containing(Vec2 p) const {
        Box2 box;
        box.extend(p);
        for (uint32_t i : surface_.near(box))
            if (point_in_ring(p, *surface_.polygon(i).outer)) return surface_.polygon(i).outer;
        return nullptr;
    }
    // A mapped tree stands where it is mapped, unless that is inside a building, road or water.
    bool takes_mapped(Vec2 p) const {
        return !buildings_.contains(p) && !surface_containing(p) && !water_.contains(p);
    }
    bool free(Vec2 p) const {
        if (water_.contains(p) || paths_.contains(p)) return false;
        for (Vec2 d : {Vec2{0, 0}, Vec2{kTrunkClearance, 0}, Vec2{-kTrunkClearance, 0}, Vec2{0, kTrunkClearance},
                       Vec2{0, -kTrunkClearance}})
            if (buildings_.contains(p + d) || surface_containing(p + d)) return false;
        return true;
    }

private:
    static std::vector<PolygonRef> water_pieces(const Scene& scene) {
        std::vector<PolygonRef> pieces;
        for (const LandCover& c : scene.land_cover)
            if (c.cover == LandCoverClass::Water || c.cover == LandCoverClass::Sea)
                pieces.push_back({&c.outer, &c.holes});
        return pieces;
    }
    const BuildingIndex buildings_, surface_, paths_, water_;
};

void place_mapped_trees(const OsmData& osm, const Projection& projection, const TreeGround& ground,
                        std::vector<Tree>& trees, ParseReport& report) {
    const size_t before = trees.size();
    for (const OsmNode& node : osm.trees) {
        Tree t = tree_from_tags(node.tags, report, ReportKind::MappedTrees);
        t.osm = {OsmType::Node, node.id};
        t.source = TreeSource::Mapped;
        Vec2 p = round_to_stored_precision(projection.to_local(node.location.lat, node.location.lon));
        if (!point_within_limit(p)) {  // a stray node: the scene loader would refuse it
            report.dropped(ReportKind::MappedTrees, ReportReason::FarFromOrigin);
            continue;
        }
        if (const Ring* ring = ground.surface_containing(p)) {
            p = push_out_of(*ring, p, kTrunkClearance + 0.05);
            report.note(ReportKind::MappedTrees, ReportReason::MovedOffRoad);
        }
        if (!ground.takes_mapped(p)) {
            report.dropped(ReportKind::MappedTrees, ReportReason::InBuildingRoadOrWater);
            continue;
        }
        t.position = p;
        trees.push_back(t);
    }
    report.kept(ReportKind::MappedTrees, static_cast<int64_t>(trees.size() - before));
}

// Tree rows: one tree every row_spacing metres along the way, half a step in from its ends.
void place_row_trees(const OsmData& osm, const Projection& projection, const TreeGround& ground,
                     const TreeParams& params, std::vector<Tree>& trees, ParseReport& report) {
    size_t row_trees = 0;
    for (const OsmWay& way : osm.tree_rows) {
        Tree proto = tree_from_tags(way.tags, report, ReportKind::TreeRowTrees);
        proto.osm = {OsmType::Way, way.id};
        proto.source = TreeSource::Row;
        std::vector<Vec2> pts;
        for (const LatLon& l : way.locations) pts.push_back(projection.to_local(l.lat, l.lon));
        double carried = 0.5 * params.row_spacing;  // distance to the next tree
        for (size_t i = 0; i + 1 < pts.size(); ++i) {
            const Vec2 a = pts[i], b = pts[i + 1];
            const double len = length(b - a);
            double s = carried;
            for (; s <= len; s += params.row_spacing) {
                const Vec2 p = round_to_stored_precision(a + (b - a) * (s / len));
                report.read(ReportKind::TreeRowTrees);
                if (!point_within_limit(p)) {
                    report.dropped(ReportKind::TreeRowTrees, ReportReason::FarFromOrigin);
                    continue;
                }
                if (!ground.free(p)) {
                    report.dropped(ReportKind::TreeRowTrees, ReportReason::OnRoadBuildingOrWater);
                    continue;
                }
                Tree t = proto;
                t.position = p;
                trees.push_back(t);
                ++row_trees;
            }
            carried = s - len;
        }
    }
    report.kept(ReportKind::TreeRowTrees, static_cast<int64_t>(row_trees));
}

// Trees scattered in one forest polygon by dart throwing with a least distance (Poisson-disk),
// seeded per polygon (its OSM object and `key`), until `budget` trees are placed; returns how many were.
// One dart in [min, max): placed as a tree if it lands in the forest, on free ground, and `r` from
// every tree so far; returns whether it was.
bool throw_dart(const LandCover& forest, Vec2 min, Vec2 max, Rng& rng, const TreeGround& ground, double r,
                PointGrid& placed, std::vector<Tree>& trees) {
    const Vec2 p = round_to_stored_precision({min.x + rng.next_double() * (max.x - min.x),
                                              min.y + rng.next_double() * (max.y - min.y)});
    const double u = rng.next_double(), v = rng.next_double(), w = rng.next_double();
    if (!point_in_ring(p, forest.outer)) return false;
    bool in_hole = false;
    for (const Ring& h : forest.holes) in_hole = in_hole || point_in_ring(p, h);
    if (in_hole || placed.any_within(p, r) || !ground.free(p)) return false;
    Tree t;
    t.osm = forest.osm;
    t.source = TreeSource::Scattered;
    t.position = p;
    t.leaf_type = u < 0.5 ? LeafType::Needleleaved : LeafType::Broadleaved;
    t.height = 12 + 10 * v;
    t.crown_diameter = (t.leaf_type == LeafType::Needleleaved ? 4 : 6) + 3 * w;
    trees.push_back(t);
    placed.add(p);
    return true;
}

size_t scatter_in_forest(const LandCover& forest, size_t key, const TreeGround& ground, const TreeParams& params,
                         uint64_t seed, size_t budget, PointGrid& placed, std::vector<Tree>& trees) {
    double area = std::fabs(signed_area(forest.outer));
    for (const Ring& h : forest.holes) area -= std::fabs(signed_area(h));
    const Box2 box = bounds_of(forest.outer);
    const double r = params.forest_spacing;
    const size_t attempts = static_cast<size_t>(std::ceil(3 * area / (r * r)));
    Rng rng(hash_keys(seed, static_cast<uint64_t>(forest.osm.id), static_cast<uint64_t>(forest.osm.type), key));
    size_t scattered = 0;
    for (size_t k = 0; k < attempts && scattered < budget; ++k)
        scattered += throw_dart(forest, box.min, box.max, rng, ground, r, placed, trees);
    return scattered;
}

// The same, block by block on a grid fixed to the origin (TreeParams::local_scatter): each block
// has darts of its own, seeded by the forest and the block, and the blocks go in four rounds by
// the parity of their column and row, so a block's darts meet only its own trees and those of
// its neighbours of earlier rounds. The trees near a point then depend on the data within a few
// blocks of it, not on the whole forest: a tile of the farm scatters what one parse does.
size_t scatter_in_forest_by_blocks(const LandCover& forest, size_t key, const TreeGround& ground,
                                   const TreeParams& params, uint64_t seed, size_t budget, PointGrid& placed,
                                   std::vector<Tree>& trees) {
    const double r = params.forest_spacing;
    const double side = std::max(64.0, 2 * r);  // same-round blocks are a block apart: beyond r
    const size_t darts = static_cast<size_t>(std::ceil(3 * side * side / (r * r)));
    const Box2 box = bounds_of(forest.outer);
    const auto x0 = static_cast<int64_t>(std::floor(box.min.x / side)), x1 = static_cast<int64_t>(std::floor(box.max.x / side));
    const auto y0 = static_cast<int64_t>(std::floor(box.min.y / side)), y1 = static_cast<int64_t>(std::floor(box.max.y / side));
    size_t scattered = 0;
    for (int round = 0; round < 4; ++round)
        for (int64_t by = y0; by <= y1; ++by)
            for (int64_t bx = x0; bx <= x1; ++bx) {
                if (((bx & 1) | ((by & 1) << 1)) != round) continue;
                Rng rng(hash_keys(seed, static_cast<uint64_t>(forest.osm.id), static_cast<uint64_t>(forest.osm.type), key,
                                  static_cast<uint64_t>(bx), static_cast<uint64_t>(by)));
                const Vec2 min(bx * side, by * side), max((bx + 1) * side, (by + 1) * side);
                for (size_t k = 0; k < darts && scattered < budget; ++k)
                    scattered += throw_dart(forest, min, max, rng, ground, r, placed, trees);
            }
    return scattered;
}

void place_forest_trees(const Scene& scene, const TreeGround& ground, const TreeParams& params, uint64_t seed,
                        std::vector<Tree>& trees, ParseReport& report) {
    PointGrid placed(std::max(params.forest_spacing, 0.5));
    for (const Tree& t : trees) placed.add(t.position);
    size_t scattered = 0;
    std::map<OsmRef, size_t> pieces;  // per OSM object, its polygons so far
    for (size_t index = 0; index < scene.land_cover.size(); ++index) {
        const LandCover& forest = scene.land_cover[index];
        const size_t piece = pieces[forest.osm]++;
        if (forest.cover != LandCoverClass::Forest) continue;
        const size_t budget = params.max_scattered - scattered;
        scattered += params.local_scatter
                         ? scatter_in_forest_by_blocks(forest, piece, ground, params, seed, budget, placed, trees)
                         : scatter_in_forest(forest, index, ground, params, seed, budget, placed, trees);
        if (scattered >= params.max_scattered) {
            report.note(ReportKind::ForestTrees, ReportReason::ForestCapReached);
            break;
        }
    }
    report.kept(ReportKind::ForestTrees, static_cast<int64_t>(scattered));
}

}  // namespace

std::vector<Tree> place_trees(const OsmData& osm, const Projection& projection, const Scene& scene,
                              const TreeParams& params, uint64_t seed, ParseReport& report) {
    std::vector<Tree> trees;
    if (params.mode == TreeMode::None) return trees;
    const TreeGround ground(scene);
    place_mapped_trees(osm, projection, ground, trees, report);
    place_row_trees(osm, projection, ground, params, trees, report);
    if (params.mode == TreeMode::Mapped) return trees;
    place_forest_trees(scene, ground, params, seed, trees, report);
    return trees;
}

}  // namespace citygen
