// Every option osmparse runs with, grouped by the stage that uses it. The defaults here
// are the one definition; the CLI (main.cpp) and the scene header (to_key_values) read them.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace citygen {

struct BuildingParams {
    uint64_t seed = 1;
    double random_min_height = 8;    // --building-min-h: used only when nothing is tagged
    double random_max_height = 30;   // --building-max-h
    double level_height = 3.0;       // metres per building:levels
    double simplify_angle_deg = 5;   // --simplify-angle: merge edges turning less than this
    double min_area = 4.0;           // slivers below this many square metres are dropped
    double max_height = 1000;        // tagged heights above this are absurd
    std::vector<std::string> ignore_types{"roof", "carport", "ruins", "construction",
                                          "proposed", "demolished", "no"};
};

struct RoadParams {
    // highway=* values that are carriageways.
    std::vector<std::string> classes{"motorway", "motorway_link", "trunk", "trunk_link",
                                     "primary", "primary_link", "secondary", "secondary_link",
                                     "tertiary", "tertiary_link", "unclassified", "residential",
                                     "living_street", "service"};
    double merge_angle_deg = 10;     // --road-merge-angle
    double lane_width = 3.0;         // metres per lane when `lanes` is tagged
    double min_width = 2.0;          // --road-min-width: narrower roads are dropped
    double max_width = 100;          // tagged widths above this are absurd
    double miter_limit = 2.0;        // miter length / half width before bevelling
};

struct SidewalkParams {
    double width = 2.0;
    double curb_height = 0.15;
};

struct LampParams {
    double spacing = 28;             // --lamp-spacing
    double min_distance_to_tagged = 12;
    double height = 6;
};

// --fill-empty-blocks: buildings generated in road-graph blocks the map left empty.
struct BlockParams {
    bool enabled = false;
    double max_lot_area = 600;     // lots are split until they are at most this big (m2)
    double min_footprint_area = 40;
    double setback = 1.0;          // metres from the sidewalk to the building, and between lots
    double min_block_area = 300;   // after leaving the sidewalk
    double max_block_area = 20000; // bigger empty blocks are parks, fields or yards
    int min_buildings_near = 5;    // mapped buildings within near_distance: the block is built-up
    double near_distance = 60;
};

// Trees (place_trees.h).
enum class TreeMode : uint8_t { None, Mapped, All };  // --trees: none, mapped (nodes and rows), all (+ forests)
struct TreeParams {
    TreeMode mode = TreeMode::All;
    double forest_spacing = 6;       // --forest-tree-spacing: least distance between scattered trees
    double row_spacing = 8;          // metres between trees of a natural=tree_row
    size_t max_scattered = 200000;   // a cap on forest trees, so a national park cannot fill memory
    // --origin (the farm's shared frame): forests scattered block by block on a grid fixed to the
    // origin, each seeded by its OSM object and its ordinal among that object's polygons (not by
    // its place in the scene's list), so the trees near a point depend only on the data near it
    // and a tile scatters what a whole-region parse does. Off otherwise: older scenes keep their trees.
    bool local_scatter = false;
};

// Terrain (osmparse/terrain/build_terrain.h): without DEM files the scene stays flat.
struct TerrainParams {
    std::vector<std::string> dem_files;  // --dem, in the order given: where DEMs overlap, the first wins
    double resolution = 0;               // --dem-resolution: metres between nodes; 0: the finest DEM's own
};

struct ParseParams {
    BuildingParams buildings;
    RoadParams roads;
    SidewalkParams sidewalks;
    LampParams lamps;
    BlockParams blocks;
    TreeParams trees;
    TerrainParams terrain;
    uint64_t seed = 1;

    // Every parameter as text, sorted by key, for the scene header and --info.
    std::vector<std::pair<std::string, std::string>> to_key_values() const;
};

}  // namespace citygen
