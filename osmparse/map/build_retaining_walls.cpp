#include "osmparse/map/build_retaining_walls.h"

#include "common/scene_limits.h"
#include "osmparse/buildings/building_colours.h"
#include "osmparse/core/osm_units.h"

namespace citygen {

std::vector<RetainingWall> build_retaining_walls(const OsmData& osm, const Projection& projection,
                                                 ParseReport& report) {
    constexpr ReportKind kRow = ReportKind::RetainingWalls;
    std::vector<RetainingWall> walls;
    int64_t previous_id = 0;
    bool first = true;
    for (const OsmWay& run : osm.retaining_walls) {
        // A way's runs come one after another: the way is read once.
        if (first || run.id != previous_id) report.read(kRow);
        first = false;
        previous_id = run.id;
        if (run.locations.size() < 2) {
            report.dropped(kRow, ReportReason::NodesMissing);
            continue;
        }
        if (run.cut_before || run.cut_after) report.note(kRow, ReportReason::ClippedAtEdge);
        RetainingWall wall;
        wall.osm = {OsmType::Way, run.id};
        for (const LatLon& l : run.locations) {
            const Vec2 p = projection.to_local(l.lat, l.lon);
            if (wall.line.empty() || p != wall.line.back()) wall.line.push_back(p);
        }
        if (wall.line.size() < 2) {
            report.dropped(kRow, ReportReason::ZeroLength);
            continue;
        }
        bool within = wall.line.size() <= kMaxRingPoints && extent_within_limit(wall.line);
        for (Vec2 p : wall.line) within = within && point_within_limit(p);
        if (!within) {
            report.dropped(kRow, ReportReason::BeyondSceneLimits);
            continue;
        }
        const char* height = run.tags.get("height");
        const std::optional<double> metres = height ? parse_osm_length(height) : std::nullopt;
        wall.height_tagged = metres && *metres > 0 && *metres <= kMaxHeight;
        wall.height = wall.height_tagged ? *metres : kDefaultRetainingWallHeight;
        if (!wall.height_tagged)
            report.note(kRow, height ? ReportReason::RetainingWallHeightUnusable : ReportReason::RetainingWallHeightDefault);
        const char* material = run.tags.get("material");
        if (!material || !parse_wall_material(material, &wall.material)) wall.material = WallMaterial::Concrete;
        walls.push_back(std::move(wall));
        report.kept(kRow);
    }
    return walls;
}

}  // namespace citygen
