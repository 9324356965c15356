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

#include "osmparse/core/osm_data.h"
#include "osmparse/core/report.h"

namespace citygen {

// What every handler of the read stage holds: the data it fills and the report it counts in.
class ReadHandler : public osmium::handler::Handler {
public:
    ReadHandler(OsmData& data, ParseReport& report) : data_(data), report_(report) {}

protected:
    OsmData& data_;
    ParseReport& report_;
};

// highway=street_lamp nodes -> data.street_lamps.
class StreetLampHandler : public ReadHandler {
public:
    using ReadHandler::ReadHandler;
    void node(const osmium::Node& node);
};

// natural=tree nodes -> data.trees; natural=tree_row ways -> data.tree_rows.
class TreeHandler : public ReadHandler {
public:
    using ReadHandler::ReadHandler;
    void node(const osmium::Node& node);
    void way(const osmium::Way& way);
};

// highway=crossing and highway=traffic_signals nodes -> data.road_marks.
class RoadMarkHandler : public ReadHandler {
public:
    using ReadHandler::ReadHandler;
    void node(const osmium::Node& node);
};

// Every way with a highway=* tag -> data.highways, cut into runs of present nodes.
// Handlers that keep highways, lamps, tree rows and building areas extend data.min/max.
class HighwayHandler : public ReadHandler {
public:
    using ReadHandler::ReadHandler;
    void way(const osmium::Way& way);
};

// natural=coastline ways -> data.coastlines, cut into runs of present nodes.
class CoastlineHandler : public ReadHandler {
public:
    using ReadHandler::ReadHandler;
    void way(const osmium::Way& way);
};

// railway=rail|tram|light_rail|subway ways -> data.railways, cut into runs of present nodes.
class RailwayHandler : public ReadHandler {
public:
    using ReadHandler::ReadHandler;
    void way(const osmium::Way& way);
};

// barrier=retaining_wall ways, closed ones too -> data.retaining_walls, cut into runs of present
// nodes. Not counted here: the walls are kept only with a height field (build_retaining_walls.h
// counts them then), so a parse without one reports what it did before.
class RetainingWallHandler : public ReadHandler {
public:
    using ReadHandler::ReadHandler;
    void way(const osmium::Way& way);
};

// man_made=pier|breakwater ways that are lines (not closed, or area=no) -> data.pier_lines, cut
// into runs of present nodes, with their width tag only. Counted, as the areas, by
// build_land_cover when it keeps them (only on a height field).
class PierLineHandler : public ReadHandler {
public:
    using ReadHandler::ReadHandler;
    void way(const osmium::Way& way);
};

// The one route of building=* and building:part=* areas into data.building_areas. way() and
// relation() count what the file holds; area() keeps what libosmium assembled. libosmium
// refuses a self-intersecting ring (it yields an empty area): then the closed way's own
// outline, kept by way() until its area arrives, goes on to the footprint clean-up, which can
// repair it. Ways must reach way() before their areas reach area(). The areas keep every tag but
// the address (addr:*), which no stage reads.
class BuildingAreaHandler : public ReadHandler {
public:
    using ReadHandler::ReadHandler;
    void way(const osmium::Way& way);
    void relation(const osmium::Relation& relation);
    void area(const osmium::Area& area);

private:
    std::unordered_map<int64_t, std::vector<LatLon>> way_outlines_;  // closed, every node present
};

// Areas with a land cover class (build_land_cover.h) -> data.land_cover_areas; others that the
// assembler's filter let through (e.g. a closed highway=pedestrian way without area=yes) are
// ignored.
class LandCoverHandler : public ReadHandler {
public:
    using ReadHandler::ReadHandler;
    void area(const osmium::Area& area);
};

bool is_building_tags(const osmium::TagList& tags);
OsmTags copy_tags(const osmium::TagList& tags);

}  // namespace citygen
