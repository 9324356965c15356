// The entry points of the GDAL module (gdal_dem_reader.cpp, built as osmparse_dem_reader.so
// beside the programs). GDAL and the hundred libraries it brings cost about 30 MB and 40 ms at
// every start of a program linking them, so osmparse loads the module (read_dem.cpp) only for
// --dem. Each entry point sets `error` to a failure's one line, or leaves it empty.
#pragma once

#include <string>
#include <vector>

#include "osmparse/terrain/read_dem.h"

extern "C" {

// Opens each file as citygen_warp_dems does.
void citygen_check_dem_files(const std::vector<std::string>& paths, std::string& error);

// The finest of the DEMs' own resolutions in the scene's metres (GDAL's suggested output cell).
void citygen_native_dem_cell(const std::vector<std::string>& paths, double origin_lat, double origin_lon,
                             double& cell, std::string& error);

// Warps the DEMs onto out.grid (laid out, heights NaN, nothing covered) in the scene's
// transverse Mercator on the origin, and fills the rest of `out` but the assumed datum.
void citygen_warp_dems(const std::vector<std::string>& paths, double origin_lat, double origin_lon,
                       citygen::DemRead& out, std::string& error);
}
