// What the read stage keeps of an OSM file: only the objects later stages use, with
// their tags and WGS84 locations. Plain data, no libosmium types, so stages and tests
// can build it by hand.
#pragma once

#include <cstdint>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

#include "common/scene.h"

namespace citygen {

struct LatLon {
    double lat = 0, lon = 0;
};

struct OsmTags {
    std::vector<std::pair<std::string, std::string>> entries;

    // The value of `key`, or nullptr when the tag is absent.
    const char* get(const char* key) const {
        for (const auto& [k, v] : entries)
            if (k == key) return v.c_str();
        return nullptr;
    }
    bool has(const char* key, const char* value) const {
        const char* v = get(key);
        return v && std::strcmp(v, value) == 0;
    }
};

struct OsmNode {
    int64_t id = 0;
    LatLon location;
    OsmTags tags;
};

// A way with the locations of its nodes. Ways clipped at the extract edge are cut into
// the runs of nodes that are present; each run keeps the way's id.
struct OsmWay {
    int64_t id = 0;
    OsmTags tags;
    std::vector<int64_t> nodes;
    std::vector<LatLon> locations;  // one per node
    // The run was cut before its first / after its last node (the way goes on through nodes
    // missing from the extract).
    bool cut_before = false, cut_after = false;
};

struct OsmPolygon {
    std::vector<LatLon> outer;               // closed: first point repeated at the end
    std::vector<std::vector<LatLon>> inners;
};

// A building or building:part area: a closed way or a multipolygon relation,
// assembled by libosmium into outer rings, each with its inner rings.
struct OsmArea {
    OsmRef ref;
    OsmTags tags;
    std::vector<OsmPolygon> polygons;
};

struct OsmData {
    std::vector<OsmNode> street_lamps;  // highway=street_lamp nodes
    std::vector<OsmWay> highways;       // every way with a highway=* tag
    std::vector<OsmArea> building_areas;  // building=* and building:part=*, tags without addr:*
    LatLon min{90, 180}, max{-90, -180};  // bounds of every kept location
    // The map beyond roads and buildings.
    std::vector<OsmArea> land_cover_areas;  // areas with a land cover class (build_land_cover.h)
    std::vector<OsmWay> pier_lines;         // man_made=pier|breakwater ways that are lines, not areas
    std::vector<OsmWay> coastlines;         // natural=coastline ways, cut into runs of present nodes
    std::vector<OsmNode> trees;             // natural=tree nodes
    std::vector<OsmNode> road_marks;        // highway=crossing and highway=traffic_signals nodes
    std::vector<OsmWay> tree_rows;          // natural=tree_row ways, cut into runs of present nodes
    std::vector<OsmWay> railways;           // railway=rail|tram|light_rail|subway ways, runs of present nodes
    std::vector<OsmWay> retaining_walls;    // barrier=retaining_wall ways (closed ones too), runs of present nodes
    // The extract's bounds from the file header (<bounds> or the PBF header box), when given.
    bool has_extract_bounds = false;
    LatLon extract_min, extract_max;
};

}  // namespace citygen
