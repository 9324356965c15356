// The whole osmparse pipeline, stage by stage (see pipeline.cpp).
#pragma once

#include <string>

#include "params.h"
#include "report.h"
#include "scene.h"

namespace citygen {

struct ParseJob {
    std::string input;
    ParseParams params;
    bool quiet = false;
    double hide_height_tags = 0;  // benchmark aid: this fraction of buildings loses its height tags
};

Scene parse_osm_to_scene(const ParseJob& job, ParseReport& report);

}  // namespace citygen
