// The handlers of the read stage (read_osm.cpp), libosmium style: each keeps one kind of
// object in OsmData and counts it in the report. read_osm applies them all in one walk over
// the file, after NodeLocationsForWays has put the node locations into the ways; the two
// area handlers see the areas libosmium assembles from closed ways and multipolygons.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include <osmium/handler.hpp>
#include <osmium/osm/area.hpp>
#include <osmium/osm/node.hpp>
#include <osmium/osm/relation.hpp>
#include <osmium/osm/way.hpp>

#include "osm_data.h"
#include "report.h"

namespace citygen {

// highway=street_lamp nodes -> data.street_lamps.
class StreetLampHandler : public osmium::handler::Handler {
public:
    StreetLampHandler(OsmData& data, ParseReport& report) : data_(data), report_(report) {}
    void node(const osmium::Node& node);

private:
    OsmData& data_;
    ParseReport& report_;
};

// natural=tree nodes -> data.trees; natural=tree_row ways -> data.tree_rows.
class TreeHandler : public osmium::handler::Handler {
public:
    TreeHandler(OsmData& data, ParseReport& report) : data_(data), report_(report) {}
    void node(const osmium::Node& node);
    void way(const osmium::Way& way);

private:
    OsmData& data_;
    ParseReport& report_;
};

// highway=crossing and highway=traffic_signals nodes -> data.road_marks.
class RoadMarkHandler : public osmium::handler::Handler {
public:
    RoadMarkHandler(OsmData& data, ParseReport& report) : data_(data), report_(report) {}
    void node(const osmium::Node& node);

private:
    OsmData& data_;
    ParseReport& report_;
};

// Every way with a highway=* tag -> data.highways, cut into runs of present nodes.
// Handlers that keep highways, lamps, tree rows and building areas extend data.min/max.
class HighwayHandler : public osmium::handler::Handler {
public:
    HighwayHandler(OsmData& data, ParseReport& report) : data_(data), report_(report) {}
    void way(const osmium::Way& way);

private:
    OsmData& data_;
    ParseReport& report_;
};

// natural=coastline ways -> data.coastlines, cut into runs of present nodes.
class CoastlineHandler : public osmium::handler::Handler {
public:
    CoastlineHandler(OsmData& data, ParseReport& report) : data_(data), report_(report) {}
    void way(const osmium::Way& way);

private:
    OsmData& data_;
    ParseReport& report_;
};

// railway=rail|tram|light_rail|subway ways -> data.railways, cut into runs of present nodes.
class RailwayHandler : public osmium::handler::Handler {
public:
    RailwayHandler(OsmData& data, ParseReport& report) : data_(data), report_(report) {}
    void way(const osmium::Way& way);

private:
    OsmData& data_;
    ParseReport& report_;
};

// The one route of building=* and building:part=* areas into data.building_areas. way() and
// relation() count what the file holds; area() keeps what libosmium assembled. libosmium
// refuses a self-intersecting ring (it yields an empty area): then the closed way's own
// outline, kept by way() until its area arrives, goes on to the footprint clean-up, which can
// repair it. Ways must reach way() before their areas reach area().
class BuildingAreaHandler : public osmium::handler::Handler {
public:
    BuildingAreaHandler(OsmData& data, ParseReport& report) : data_(data), report_(report) {}
    void way(const osmium::Way& way);
    void relation(const osmium::Relation& relation);
    void area(const osmium::Area& area);

private:
    OsmData& data_;
    ParseReport& report_;
    std::unordered_map<int64_t, std::vector<LatLon>> way_outlines_;  // closed, every node present
};

// Areas with a land cover class (build_land_cover.h) -> data.land_cover_areas; others that the
// assembler's filter let through (e.g. a closed highway=pedestrian way without area=yes) are
// ignored.
class LandCoverHandler : public osmium::handler::Handler {
public:
    LandCoverHandler(OsmData& data, ParseReport& report) : data_(data), report_(report) {}
    void area(const osmium::Area& area);

private:
    OsmData& data_;
    ParseReport& report_;
};

bool is_building_tags(const osmium::TagList& tags);
OsmTags copy_tags(const osmium::TagList& tags);

}  // namespace citygen
