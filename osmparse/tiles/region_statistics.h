// What the tiles of a region parsed on the farm share (docs/farm.md): the statistics that the
// height and roof rules read of the whole extract. Each tile gathers them over its core box
// (osmparse --write-region-statistics); the tiles' files concatenated are the region's, and each
// tile's parse then reads those (--region-statistics) instead of its own extract's, so it guesses
// heights and roofs as one parse of the region does.
#pragma once

#include <string>
#include <vector>

#include "osmparse/buildings/infer_heights.h"
#include "osmparse/roofs/build_roofs.h"

namespace citygen {

struct RegionStatistics {
    HeightEvidence heights;
    RoofEvidence roofs;
};

// Text, one record a line, so that concatenated files are their sum. Each part opens with the
// line "citygen-region-statistics 1" and closes with "end N" (its N records), so a cut file is
// refused:
//   tagged CLASS HEIGHT TYPE      a tagged building (HEIGHT a hexadecimal float, TYPE with '%',
//                                 spaces and control bytes as %XX)
//   ratio GROUP LOG_RATIO         a calibration ratio (a hexadecimal float)
//   roofs GROUP TAGGED PITCHED    a roof group's counts
std::string region_statistics_text(const RegionStatistics& statistics);
// Sums the parts of `text`; throws Error naming `path` and the line for anything malformed,
// out of range or cut.
RegionStatistics parse_region_statistics(const std::string& text, const std::string& path);

// The sum of the files (each read as parse_region_statistics reads its text).
RegionStatistics read_region_statistics(const std::vector<std::string>& paths);
// Atomically (write_file_atomically), checked by parse_region_statistics first.
void write_region_statistics(const std::string& path, const RegionStatistics& statistics);

}  // namespace citygen
