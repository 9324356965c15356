#include "osmparse/map/fill_empty_blocks.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <optional>

#include "common/rng.h"
#include "osmparse/buildings/building_colours.h"
#include "osmparse/buildings/building_tags.h"
#include "osmparse/buildings/infer_heights.h"
#include "osmparse/polygons/clean_footprint.h"
#include "osmparse/polygons/polygon_overlap.h"
#include "osmparse/polygons/ring_is_simple.h"
#include "osmparse/roofs/build_roofs.h"
#include "osmparse/roofs/roof_geometry.h"
#include "osmparse/roofs/roof_skeleton.h"

namespace citygen {

namespace {

enum Salt : uint64_t { kJitter = 401 };

struct Block {
    Ring ring;              // counter-clockwise, along the road centrelines
    double widest = 0;      // widest road around it (m)
};

// Bounded faces of the road graph: walk every half-edge keeping the face on its left, turning
// as far left as possible at each node. Dead ends are pruned first (they are no block's side).
std::vector<Block> road_blocks(const Scene& scene) {
    const size_t n = scene.roads.size();
    std::vector<bool> alive(n, false);
    std::map<int64_t, int> degree;
    for (size_t r = 0; r < n; ++r) {
        const RoadEdge& e = scene.roads[r];
        if (e.centreline.size() < 2 || e.from_node == e.to_node) continue;
        alive[r] = true;
        ++degree[e.from_node];
        ++degree[e.to_node];
    }
    for (bool pruned = true; pruned;) {
        pruned = false;
        for (size_t r = 0; r < n; ++r) {
            const RoadEdge& e = scene.roads[r];
            if (!alive[r] || (degree[e.from_node] > 1 && degree[e.to_node] > 1)) continue;
            alive[r] = false;
            --degree[e.from_node];
            --degree[e.to_node];
            pruned = true;
        }
    }
    // Half-edge h: road h / 2, forwards when h is even.
    auto tail = [&](size_t h) { const RoadEdge& e = scene.roads[h / 2]; return h % 2 ? e.to_node : e.from_node; };
    auto head = [&](size_t h) { const RoadEdge& e = scene.roads[h / 2]; return h % 2 ? e.from_node : e.to_node; };
    auto points = [&](size_t h) {
        std::vector<Vec2> p = scene.roads[h / 2].centreline;
        if (h % 2) std::reverse(p.begin(), p.end());
        return p;
    };
    std::map<int64_t, std::vector<std::pair<double, size_t>>> outgoing;  // by angle
    for (size_t h = 0; h < 2 * n; ++h) {
        if (!alive[h / 2]) continue;
        const std::vector<Vec2> p = points(h);
        const Vec2 d = p[1] - p[0];
        outgoing[tail(h)].push_back({std::atan2(d.y, d.x), h});
    }
    for (auto& [node, list] : outgoing) std::sort(list.begin(), list.end());
    std::vector<bool> used(2 * n, false);
    std::vector<Block> blocks;
    for (size_t start = 0; start < 2 * n; ++start) {
        if (!alive[start / 2] || used[start]) continue;
        Block block;
        bool closed = false;
        for (size_t h = start, steps = 0; steps < 4 * n; ++steps) {
            used[h] = true;
            const std::vector<Vec2> p = points(h);
            block.ring.insert(block.ring.end(), p.begin(), p.end() - 1);
            block.widest = std::max(block.widest, scene.roads[h / 2].width);
            const auto& list = outgoing[head(h)];
            size_t twin_at = 0;
            for (size_t i = 0; i < list.size(); ++i)
                if (list[i].second == (h ^ 1)) twin_at = i;
            h = list[(twin_at + list.size() - 1) % list.size()].second;
            if (h == start) {
                closed = true;
                break;
            }
            if (used[h]) break;
        }
        if (!closed) continue;
        block.ring = remove_repeated_and_collinear(block.ring);
        if (block.ring.size() >= 3 && signed_area(block.ring) > 0 && ring_is_simple(block.ring))
            blocks.push_back(std::move(block));
    }
    return blocks;
}

// Lots: split across the long axis of the minimum-area rectangle until small enough.
void split_into_lots(const Ring& lot, double max_area, int depth, std::vector<Ring>& lots) {
    const double area = signed_area(lot);
    if (area <= max_area || depth > 12) {
        lots.push_back(lot);
        return;
    }
    const RoofFrame frame = roof_frame(lot, RoofSpec{});
    const double middle = dot(frame.centre, frame.along) + 0.5 * (frame.s0 + frame.s1);
    std::vector<Ring> below, above;
    if (!split_off(lot, frame.along, middle, &below) || !split_off(lot, frame.along * -1.0, -middle, &above)) {
        lots.push_back(lot);
        return;
    }
    for (const std::vector<Ring>* side : {&below, &above})
        for (const Ring& piece : *side) {
            const Ring clean = remove_repeated_and_collinear(piece);
            if (clean.size() >= 3 && signed_area(clean) > 1) split_into_lots(clean, max_area, depth + 1, lots);
        }
}

// Whether one of the lot's sides lies on the street side of its block.
bool has_street_access(const Ring& lot, const Ring& block) {
    for (size_t i = 0, n = lot.size(); i < n; ++i)
        if (distance_to_boundary((lot[i] + lot[(i + 1) % n]) * 0.5, block) < 1e-3) return true;
    return false;
}

// Roads, joints and sidewalks as footprints (counter-clockwise), to keep generated buildings off them.
std::vector<Building> surface_pieces(const Scene& scene) {
    std::vector<Building> surfaces;
    auto add_surface = [&](const Ring& ring) {
        Building piece;
        piece.outer = ring;
        if (signed_area(piece.outer) < 0) std::reverse(piece.outer.begin(), piece.outer.end());
        surfaces.push_back(std::move(piece));
    };
    for (const RoadEdge& r : scene.roads) add_surface(r.quad);
    for (const Joint& j : scene.joints) add_surface(j.polygon);
    for (const Sidewalk& w : scene.sidewalks) add_surface(w.polygon);
    return surfaces;
}

// What a generated building must keep clear of: the mapped buildings and the street surfaces.
struct Occupied {
    const Scene& scene;
    BuildingIndex buildings;
    std::vector<Building> surfaces;
    BuildingIndex surface_index;

    explicit Occupied(const Scene& s)
        : scene(s), buildings(s.buildings), surfaces(surface_pieces(s)), surface_index(surfaces) {}
    double overlap(const Ring& footprint) const {
        double area = 0;
        for (uint32_t i : surface_index.near(bounds_of(footprint))) area += overlap_area(footprint, surfaces[i]);
        for (uint32_t i : buildings.near(bounds_of(footprint))) area += overlap_area(footprint, scene.buildings[i]);
        return area;
    }
};

// A block is filled when no mapped building stands in it but enough stand near it.
bool block_wants_buildings(const Block& block, const Occupied& occupied, const BlockParams& params,
                           ParseReport& report) {
    Box2 box = bounds_of(block.ring);
    for (uint32_t i : occupied.buildings.near(box))
        if (point_in_ring(interior_point(occupied.scene.buildings[i].outer), block.ring)) return false;
    box.extend(box.min - Vec2{params.near_distance, params.near_distance});
    box.extend(box.max + Vec2{params.near_distance, params.near_distance});
    if (static_cast<int>(occupied.buildings.near(box).size()) < params.min_buildings_near) {
        report.note(ReportKind::GeneratedBuildings, ReportReason::BlockNotBuiltUp);
        return false;
    }
    return true;
}

// The footprint of a lot's building: the lot set back, if it reaches the street, is large enough
// and overlaps nothing (counted when not).
std::optional<Ring> lot_footprint(const Ring& lot, const Ring& inside, const Occupied& occupied,
                                  const BlockParams& params, ParseReport& report) {
    report.read(ReportKind::GeneratedBuildings);
    if (!has_street_access(lot, inside)) {
        report.dropped(ReportKind::GeneratedBuildings, ReportReason::LotWithoutAccess);
        return std::nullopt;
    }
    std::vector<Ring> shrunk;
    if (!inset_polygon(lot, params.setback, &shrunk) || shrunk.empty()) {
        report.dropped(ReportKind::GeneratedBuildings, ReportReason::LotTooSmall);
        return std::nullopt;
    }
    const Ring footprint = *std::max_element(shrunk.begin(), shrunk.end(), [](const Ring& a, const Ring& b) {
        return signed_area(a) < signed_area(b);
    });
    if (signed_area(footprint) < params.min_footprint_area || !ring_is_simple(footprint)) {
        report.dropped(ReportKind::GeneratedBuildings, ReportReason::LotTooSmall);
        return std::nullopt;
    }
    // Never on a road, joint, sidewalk or mapped building (the setbacks should see to it).
    if (occupied.overlap(footprint) > 1e-3) {
        report.dropped(ReportKind::GeneratedBuildings, ReportReason::LotOverlaps);
        return std::nullopt;
    }
    return footprint;
}

// A generated building's height: the type-and-area rule for `building=yes`, jittered by its id.
Building generated_building(Ring footprint, size_t index, const BuildingParams& buildings) {
    Building b;
    b.osm = {OsmType::Way, -static_cast<int64_t>(index + 1)};
    b.outer = std::move(footprint);
    b.type = "yes";
    b.generated = true;
    bool sure = false;
    const double by_type = height_by_type_and_area(b.type, signed_area(b.outer), &sure);
    const double u = hash_to_unit(hash_keys(buildings.seed, static_cast<uint64_t>(b.osm.type),
                                            static_cast<uint64_t>(b.osm.id), kJitter));
    b.height = by_type * (0.9 + 0.2 * u);
    b.height_source = HeightSource::Random;
    b.height_rule = HeightRule::TypeAndArea;
    b.levels = std::max(1, static_cast<int>(std::lround(b.height / buildings.level_height)));
    return b;
}

}  // namespace

std::vector<Building> fill_empty_blocks(const Scene& scene, const BuildingParams& buildings,
                                        const BlockParams& params, double sidewalk_width,
                                        const RoofEvidence& roof_evidence, ParseReport& report) {
    std::vector<Building> generated;
    if (!params.enabled) return generated;
    const Occupied occupied(scene);
    for (const Block& block : road_blocks(scene)) {
        report.read(ReportKind::GeneratedBuildings, 0);
        if (!block_wants_buildings(block, occupied, params, report)) continue;
        std::vector<Ring> insides;
        if (!inset_polygon(block.ring, 0.5 * block.widest + sidewalk_width + params.setback, &insides)) continue;
        for (const Ring& inside : insides) {
            const double area = signed_area(inside);
            if (area < params.min_block_area || area > params.max_block_area) {
                report.note(ReportKind::GeneratedBuildings, ReportReason::BlockSizeOutOfRange);
                continue;
            }
            report.note(ReportKind::GeneratedBuildings, ReportReason::BlockFilled);
            std::vector<Ring> lots;
            split_into_lots(inside, params.max_lot_area, 0, lots);
            for (const Ring& lot : lots)
                if (std::optional<Ring> footprint = lot_footprint(lot, inside, occupied, params, report))
                    generated.push_back(generated_building(std::move(*footprint), generated.size(), buildings));
        }
    }
    // Roofs, colours and materials by the same default rules as untagged mapped buildings.
    const OsmData no_tags;
    const BuildingTagIndex tags(no_tags);
    build_roofs(generated, tags, buildings, report, &roof_evidence);
    choose_colours_and_materials(generated, tags, buildings, report);
    report.kept(ReportKind::GeneratedBuildings, static_cast<int64_t>(generated.size()));
    return generated;
}

}  // namespace citygen
