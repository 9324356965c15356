#include "osmparse/core/params.h"

#include <algorithm>
#include <cstdio>

namespace citygen {

namespace {
std::string number(double v) {
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9g", v);  // locale-free and deterministic
    return buf;
}
std::string joined(const std::vector<std::string>& items) {
    std::string out;
    for (const std::string& s : items) out += (out.empty() ? "" : ",") + s;
    return out;
}
}  // namespace

std::vector<std::pair<std::string, std::string>> ParseParams::to_key_values() const {
    std::vector<std::pair<std::string, std::string>> kv{
        {"seed", std::to_string(seed)},
        {"building-min-h", number(buildings.random_min_height)},
        {"building-max-h", number(buildings.random_max_height)},
        {"building-level-height", number(buildings.level_height)},
        {"simplify-angle", number(buildings.simplify_angle_deg)},
        {"building-min-area", number(buildings.min_area)},
        {"ignore-building-types", joined(buildings.ignore_types)},
        {"road-classes", joined(roads.classes)},
        {"road-merge-angle", number(roads.merge_angle_deg)},
        {"road-lane-width", number(roads.lane_width)},
        {"road-min-width", number(roads.min_width)},
        {"road-miter-limit", number(roads.miter_limit)},
        {"sidewalk-width", number(sidewalks.width)},
        {"curb-height", number(sidewalks.curb_height)},
        {"lamp-spacing", number(lamps.spacing)},
        {"lamp-min-distance", number(lamps.min_distance_to_tagged)},
        {"lamp-height", number(lamps.height)},
        {"trees", trees.mode == TreeMode::None ? "none" : trees.mode == TreeMode::Mapped ? "mapped" : "all"},
        {"forest-tree-spacing", number(trees.forest_spacing)},
        {"tree-row-spacing", number(trees.row_spacing)},
    };
    if (blocks.enabled) kv.push_back({"fill-empty-blocks", "true"});  // only when on: older headers unchanged
    if (!terrain.dem_files.empty()) {  // the same: only with a DEM
        std::vector<std::string> names;  // base names only, as the header's source
        for (const std::string& path : terrain.dem_files) names.push_back(path.substr(path.find_last_of('/') + 1));
        kv.push_back({"dem", joined(names)});
        kv.push_back({"dem-resolution", terrain.resolution > 0 ? number(terrain.resolution) : "native"});
    }
    std::sort(kv.begin(), kv.end());
    return kv;
}

}  // namespace citygen
