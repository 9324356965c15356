#include "osmparse/buildings/build_buildings.h"

#include <algorithm>
#include <cstring>
#include <iterator>
#include <optional>

#include <tbb/parallel_for.h>

#include "common/scene_limits.h"
#include "osmparse/buildings/building_heights.h"
#include "osmparse/polygons/clean_footprint.h"

namespace citygen {

namespace {

Ring project_ring(const std::vector<LatLon>& points, const Projection& projection) {
    Ring ring;
    ring.reserve(points.size());
    for (const LatLon& p : points) {
        // Rings are closed: the last point repeats the first, already projected (projecting is costly).
        const bool closing = ring.size() + 1 == points.size() && ring.size() > 1 &&
                             p.lat == points.front().lat && p.lon == points.front().lon;
        ring.push_back(closing ? ring.front() : round_to_stored_precision(projection.to_local(p.lat, p.lon)));
    }
    return ring;
}

// Why a projected ring is beyond the scene limits (scene_limits.h), or nullopt. Such outlines
// are mapping mistakes (a node moved across the map); their cost must not reach later stages.
std::optional<ReportReason> ring_beyond_limits(const Ring& ring) {
    if (ring.size() > kMaxRingPoints + 1) return ReportReason::TooManyPoints;
    if (!extent_within_limit(ring, kMaxObjectExtent)) return ReportReason::TooLarge;
    if (!std::all_of(ring.begin(), ring.end(), [](Vec2 p) { return point_within_limit(p); }))
        return ReportReason::FarFromOrigin;
    return std::nullopt;
}

bool is_ignored(const std::string& type, const BuildingParams& params) {
    return std::find(params.ignore_types.begin(), params.ignore_types.end(), type) != params.ignore_types.end();
}

// Parts replace the outline they lie in: an outline holding the interior point of at
// least one part is dropped. Parts are found through their points sorted by x.
std::vector<Building> replace_outlines_by_parts(std::vector<Building> buildings, ParseReport& report) {
    std::vector<std::pair<Vec2, size_t>> part_points;
    for (size_t i = 0; i < buildings.size(); ++i)
        if (buildings[i].is_part) part_points.push_back({interior_point(buildings[i].outer), i});
    std::sort(part_points.begin(), part_points.end(),
              [](const auto& a, const auto& b) { return a.first.x < b.first.x; });
    std::vector<bool> replaced(buildings.size(), false), part_has_outline(buildings.size(), false);
    for (size_t i = 0; i < buildings.size(); ++i) {
        const Building& outline = buildings[i];
        if (outline.is_part) continue;
        const Box2 box = bounds_of(outline.outer);
        auto first = std::lower_bound(part_points.begin(), part_points.end(), box.min.x,
                                      [](const auto& entry, double x) { return entry.first.x < x; });
        for (auto it = first; it != part_points.end() && it->first.x <= box.max.x; ++it) {
            const Vec2 p = it->first;
            if (p.y < box.min.y || p.y > box.max.y || !point_in_ring(p, outline.outer)) continue;
            bool in_hole = false;
            for (const Ring& hole : outline.holes) in_hole |= point_in_ring(p, hole);
            if (in_hole) continue;
            replaced[i] = true;
            part_has_outline[it->second] = true;
        }
    }
    std::vector<Building> kept;
    kept.reserve(buildings.size());
    for (size_t i = 0; i < buildings.size(); ++i) {
        if (replaced[i]) {
            report.dropped(ReportKind::Buildings, ReportReason::ReplacedByParts);
            continue;
        }
        if (buildings[i].is_part && !part_has_outline[i])
            report.note(ReportKind::BuildingParts, ReportReason::PartOutsideOutline);
        kept.push_back(std::move(buildings[i]));
    }
    return kept;
}

// The buildings of one area, with what happened to them in `report`.
std::vector<Building> build_area(const OsmArea& area, const Projection& projection, const BuildingParams& params,
                                 ParseReport& report) {
    std::vector<Building> buildings;
    const char* part_value = area.tags.get("building:part");
    const bool is_part = part_value && std::strcmp(part_value, "no") != 0;
    const ReportKind kind = is_part ? ReportKind::BuildingParts : ReportKind::Buildings;
    const char* building_value = area.tags.get("building");
    const std::string type = is_part ? part_value : (building_value ? building_value : "no");
    report.read(kind, static_cast<int64_t>(area.polygons.size()));
    if (is_ignored(type, params)) {
        report.dropped(kind, ReportReason::IgnoredType, static_cast<int64_t>(area.polygons.size()));
        return buildings;
    }
    const BuildingHeight height = building_height(area.tags, area.ref, params, report, kind);
    for (const OsmPolygon& polygon : area.polygons) {
        std::vector<Ring> holes;
        for (const std::vector<LatLon>& inner : polygon.inners) holes.push_back(project_ring(inner, projection));
        Ring outer = project_ring(polygon.outer, projection);
        std::optional<ReportReason> beyond = ring_beyond_limits(outer);
        for (const Ring& hole : holes) beyond = beyond ? beyond : ring_beyond_limits(hole);
        if (beyond) {
            report.dropped(kind, *beyond);
            continue;
        }
        for (Footprint& footprint : clean_footprint(outer, holes, params, report, kind)) {
            Building b;
            b.osm = area.ref;
            b.outer = std::move(footprint.outer);
            b.holes = std::move(footprint.holes);
            b.min_height = height.min_height;
            b.height = height.height;
            b.levels = height.levels;
            b.height_source = height.source;
            b.type = type;
            b.is_part = is_part;
            buildings.push_back(std::move(b));
        }
    }
    return buildings;
}

}  // namespace

std::vector<Building> build_buildings(const OsmData& osm, const Projection& projection,
                                      const BuildingParams& params, ParseReport& report) {
    // Areas are independent (the footprint clean-up is most of the stage's time): in parallel, in
    // fixed blocks of areas, each block with a report of its own, merged in block order so that
    // neither the buildings nor the report depend on the threads.
    constexpr size_t kBlock = 256;
    const size_t n = osm.building_areas.size(), blocks = (n + kBlock - 1) / kBlock;
    std::vector<std::vector<Building>> per_block(blocks);
    std::vector<ParseReport> block_reports(blocks);
    tbb::parallel_for(size_t{0}, blocks, [&](size_t block) {
        for (size_t i = block * kBlock; i < std::min(n, (block + 1) * kBlock); ++i) {
            std::vector<Building> built = build_area(osm.building_areas[i], projection, params, block_reports[block]);
            std::move(built.begin(), built.end(), std::back_inserter(per_block[block]));
        }
    });
    std::vector<Building> buildings;
    for (size_t block = 0; block < blocks; ++block) {
        report.merge(block_reports[block]);
        std::move(per_block[block].begin(), per_block[block].end(), std::back_inserter(buildings));
    }
    // Same identity keeps assembly order (ring by ring), which libosmium makes stable.
    std::stable_sort(buildings.begin(), buildings.end(), [](const Building& a, const Building& b) {
        return a.osm < b.osm;
    });
    buildings = replace_outlines_by_parts(std::move(buildings), report);
    for (const Building& b : buildings) report.kept(b.is_part ? ReportKind::BuildingParts : ReportKind::Buildings);
    return buildings;
}

}  // namespace citygen
