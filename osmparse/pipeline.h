// The whole osmparse pipeline, stage by stage (see pipeline.cpp).
#pragma once

#include <optional>
#include <string>

#include "common/scene.h"
#include "osmparse/core/params.h"
#include "osmparse/core/report.h"
#include "osmparse/tiles/lat_lon_text.h"
#include "osmparse/tiles/region_statistics.h"

namespace citygen {

struct ParseJob {
    std::string input;
    ParseParams params;
    bool quiet = false;
    double hide_height_tags = 0;  // benchmark aid: this fraction of buildings loses its height tags
    double hide_roof_tags = 0;    // benchmark aid: this fraction of buildings loses its roof:shape tag
    int threads = 0;              // --threads: at most this many threads for the stages (0: every core)
    // The farm's tiles (docs/farm.md): the projection's origin given, not computed from the data,
    // so tiles share one frame; only the objects anchored in this box are kept.
    std::optional<LatLon> origin;           // --origin
    std::optional<LatLonBox> keep_inside;   // --keep-inside
    // --region-statistics: what the height and roof rules read of the whole region, gathered
    // over every tile, instead of this extract's own.
    std::optional<RegionStatistics> region_statistics;
};

// The same scene and the same report rows whatever job.threads is.
Scene parse_osm_to_scene(const ParseJob& job, ParseReport& report);

// The statistics the height and roof rules read (region_statistics.h), of the buildings anchored
// in job.keep_inside (all without it): only the stages up to the heights run.
RegionStatistics gather_region_statistics(const ParseJob& job, ParseReport& report);

// Parses and writes the scene file at `path` (save_scene's atomic write): the bytes of
// save_scene(parse_osm_to_scene(job)), at a lower peak memory, as each part of the scene is
// encoded as soon as it is final and then freed.
void parse_osm_to_file(const ParseJob& job, ParseReport& report, const std::string& path);

}  // namespace citygen
