// Parsing an OSM file in a test, the way `osmparse -q` does.
#pragma once

#include <string>

#include "osmparse/pipeline.h"

namespace citygen::test {

inline Scene parse_quietly(const std::string& path, ParseReport& report, const ParseParams& params = ParseParams{}) {
    ParseJob job;
    job.input = path;
    job.params = params;
    job.quiet = true;
    return parse_osm_to_scene(job, report);
}

}  // namespace citygen::test
