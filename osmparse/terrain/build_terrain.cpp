#include "osmparse/terrain/build_terrain.h"

#include <algorithm>
#include <cmath>

#include "osmparse/terrain/fill_dem_voids.h"
#include "common/grid_nodes.h"
#include "osmparse/terrain/read_dem.h"

namespace citygen {

std::vector<uint8_t> sea_mask(const DemGrid& g, const std::vector<LandCover>& land_cover) {
    std::vector<uint8_t> sea;
    for (const LandCover& c : land_cover) {
        if (c.cover != LandCoverClass::Sea) continue;
        if (sea.empty()) sea.assign(g.size(), 0);
        std::vector<const Ring*> rings{&c.outer};
        for (const Ring& hole : c.holes) rings.push_back(&hole);
        for_each_node_inside({g.origin, g.cell, g.nx, g.ny}, rings, [&](uint32_t i, uint32_t j) { sea[g.index(i, j)] = 1; });
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
