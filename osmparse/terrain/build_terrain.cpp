#include "osmparse/terrain/build_terrain.h"

#include <algorithm>
#include <cmath>

#include "osmparse/terrain/fill_dem_voids.h"
#include "osmparse/terrain/read_dem.h"

namespace citygen {

std::vector<uint8_t> sea_mask(const DemGrid& g, const std::vector<LandCover>& land_cover) {
    std::vector<uint8_t> sea;
    std::vector<double> crossings;
    for (const LandCover& c : land_cover) {
        if (c.cover != LandCoverClass::Sea) continue;
        if (sea.empty()) sea.assign(g.size(), 0);
        std::vector<const Ring*> rings{&c.outer};
        for (const Ring& hole : c.holes) rings.push_back(&hole);
        // Row by row: the nodes between pairs of boundary crossings (even-odd, so holes are left out).
        for (uint32_t j = 0; j < g.ny; ++j) {
            const double y = g.origin.y + j * g.cell;
            crossings.clear();
            for (const Ring* ring : rings)
                for (size_t a = 0; a < ring->size(); ++a) {
                    const Vec2 p = (*ring)[a], q = (*ring)[(a + 1) % ring->size()];
                    if ((p.y <= y) != (q.y <= y)) crossings.push_back(p.x + (y - p.y) / (q.y - p.y) * (q.x - p.x));
                }
            std::sort(crossings.begin(), crossings.end());
            for (size_t m = 0; m + 1 < crossings.size(); m += 2) {
                const double first = std::ceil((crossings[m] - g.origin.x) / g.cell);
                const double last = std::floor((crossings[m + 1] - g.origin.x) / g.cell);
                for (double i = std::max(first, 0.0); i <= std::min(last, g.nx - 1.0); ++i)
                    sea[g.index(static_cast<uint32_t>(i), j)] = 1;
            }
        }
    }
    return sea;
}

namespace {

void report_terrain(const DemRead& dem, const VoidCounts& counts, size_t files, ParseReport& report) {
    auto note = [&](ReportKind kind, ReportReason what, int64_t n) { if (n > 0) report.note(kind, what, n); };
    using R = ReportReason;
    const auto used = static_cast<int64_t>(dem.files_used);
    const auto in_feet = static_cast<int64_t>(dem.files_in_feet);
    const auto named = static_cast<int64_t>(dem.files_naming_datum);
    const auto ellipsoidal = static_cast<int64_t>(dem.files_above_ellipsoid);
    report.read(ReportKind::DemFiles, static_cast<int64_t>(files));
    report.kept(ReportKind::DemFiles, used);
    note(ReportKind::DemFiles, R::DemOutsideExtract, static_cast<int64_t>(dem.unused.size()));
    note(ReportKind::DemFiles, R::DemHeightsInFeet, in_feet);
    note(ReportKind::DemFiles, R::DemVerticalDatumNamed, named);
    note(ReportKind::DemFiles, R::DemHeightsAboveEllipsoid, ellipsoidal);
    note(ReportKind::DemFiles, R::DemVerticalDatumAssumed, used - named - ellipsoidal);
    const auto nodes = static_cast<int64_t>(dem.grid.size());
    report.read(ReportKind::TerrainNodes, nodes);
    report.kept(ReportKind::TerrainNodes, nodes);
    note(ReportKind::TerrainNodes, R::TerrainVoidFilled, counts.filled);
    note(ReportKind::TerrainNodes, R::TerrainVoidAtCoast, counts.sea);
    note(ReportKind::TerrainNodes, R::TerrainOutsideEveryDem, counts.outside);
    note(ReportKind::TerrainNodes, R::TerrainHeightBeyondLimits, counts.out_of_range);
}

}  // namespace

HeightField build_terrain(const SceneHeader& header, const Projection& projection,
                          const std::vector<LandCover>& land_cover, const TerrainParams& params,
                          ParseReport& report) {
    Box2 bounds;
    bounds.extend(header.bounds_min);
    bounds.extend(header.bounds_max);
    DemRead dem = read_dem({params.dem_files, bounds, params.resolution}, projection);
    const VoidCounts counts = fill_dem_voids(dem.grid, sea_mask(dem.grid, land_cover));
    report_terrain(dem, counts, params.dem_files.size(), report);

    HeightField field;
    field.origin = dem.grid.origin;
    field.cell = dem.grid.cell;
    field.nx = dem.grid.nx;
    field.ny = dem.grid.ny;
    const float lowest = *std::min_element(dem.grid.heights.begin(), dem.grid.heights.end());
    field.reference_altitude = std::max(0.0, std::floor(static_cast<double>(lowest)));
    field.heights = std::move(dem.grid.heights);
    for (float& h : field.heights) h = static_cast<float>(h - field.reference_altitude);
    field.vertical_datum = dem.vertical_datum;
    return field;
}

}  // namespace citygen
