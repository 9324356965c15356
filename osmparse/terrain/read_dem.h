// Reading elevation rasters (DEMs) with GDAL into a grid over the scene. Any raster GDAL reads:
// SRTM .hgt (also zipped, .hgt.zip), GeoTIFF in any CRS, VRT mosaics. Each is warped into the
// scene's transverse Mercator over only the scene's window (bilinear, no data kept as NaN), so a
// national DEM of many GB is never read whole. GDAL itself is in a module loaded on first use
// (gdal/gdal_dem_reader.h says why).
#pragma once

#include <string>
#include <vector>

#include "common/geometry.h"
#include "common/projection.h"
#include "osmparse/terrain/dem_grid.h"

namespace citygen {

// The vertical datum named when a DEM names none: SRTM's, which most DEMs users bring are
// close to (national DEMs use their own geoid, within a metre or two of it).
constexpr const char* kAssumedVerticalDatum = "EGM96 geoid (assumed: the DEM names no vertical datum)";

// Nodes the grid reaches beyond the scene's bounds on each side.
constexpr int kDemMarginCells = 2;

struct DemRequest {
    std::vector<std::string> paths;  // read in this order: where DEMs overlap, the first with a height wins
    Box2 bounds;                     // the scene's bounds, local metres
    double cell = 0;                 // metres between nodes; 0: default_field_cell of the finest DEM's
};

// A DEM's extent in degrees, for the message when none overlaps the extract.
struct DemExtent {
    std::string path;
    bool known = false;
    double lat0 = 0, lon0 = 0, lat1 = 0, lon1 = 0;
};

struct DemRead {
    DemGrid grid;                     // heights in metres (feet converted), NaN where no DEM has one
    std::string vertical_datum;       // the first overlapping DEM's that names one, else kAssumedVerticalDatum
    size_t files_used = 0;            // the DEMs that overlap the bounds, of which:
    size_t files_in_feet = 0;         //   heights in feet, converted to metres
    size_t files_naming_datum = 0;    //   a vertical datum named by their CRS
    size_t files_above_ellipsoid = 0; //   heights above the ellipsoid (a 3D CRS), not sea level
    std::vector<DemExtent> unused;    // the others
};

// Opens each file as read_dem will (a .zip through /vsizip/), so a missing, unreadable or
// unsupported file fails before a long parse. Throws Error with one line naming the file. No
// files: nothing is loaded.
void check_dem_files(const std::vector<std::string>& paths);

// Reads the DEMs over the bounds in `projection`. Throws Error with one line when a file cannot
// be read, when no DEM overlaps the bounds, or when the grid would exceed kMaxHeightFieldNodes.
DemRead read_dem(const DemRequest& request, const Projection& projection);

// The grid spacing for a DEM resolution in metres: two significant digits, at least 1 m.
double rounded_dem_cell(double metres);

// The field's default cell (metres): fine enough that the cells under a road lie within the
// corridor it is fitted in (fit_terrain.h), so the road comes out level across; the DEM's own
// resolution where that is finer; coarser where the grid over the bounds would pass
// kDefaultFieldNodes (64 MB of heights: 12 x 12 km at 3 m).
constexpr double kRoadFitCell = 3;
constexpr uint64_t kDefaultFieldNodes = uint64_t(1) << 24;
double default_field_cell(double dem_cell, const Box2& bounds);

}  // namespace citygen
