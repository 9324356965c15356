// The in-memory scene: plain data that osmparse produces and render consumes.
// scene_io.h converts it to and from the on-disk format defined in schema/scene.fbs.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "common/geometry.h"

namespace citygen {

constexpr uint16_t kSceneFormatMajor = 1;
constexpr uint16_t kSceneFormatMinor = 2;

enum class OsmType : uint8_t { Node = 0, Way = 1, Relation = 2 };

struct OsmRef {
    OsmType type = OsmType::Way;
    int64_t id = 0;
    bool operator==(const OsmRef& o) const { return type == o.type && id == o.id; }
    bool operator<(const OsmRef& o) const { return type != o.type ? type < o.type : id < o.id; }
};

std::string to_string(OsmRef ref);  // "w123", "r45", "n6"

enum class HeightSource : uint8_t { Tagged = 0, Levels = 1, Random = 2 };

// Format 1.1: roof shapes, height rules, colours and materials (schema/scene.fbs).
enum class RoofShape : uint8_t {
    Flat = 0, Skillion, Gabled, Hipped, HalfHipped, Pyramidal, Gambrel, Mansard, Dome, Onion, Round
};
constexpr int kRoofShapeCount = 11;
const char* to_string(RoofShape shape);  // the roof:shape value, e.g. "half-hipped"

enum class RoofFaceKind : uint8_t { Roof = 0, Gable = 1 };

// A planar face, counter-clockwise seen from its front (outside).
struct RoofFace {
    std::vector<Vec3> points;
    RoofFaceKind kind = RoofFaceKind::Roof;
};

enum class HeightRule : uint8_t { Tagged = 0, Levels, Neighbours, TypeAndArea, Random };
const char* to_string(HeightRule rule);

enum class WallMaterial : uint8_t { Plaster = 0, Brick, Concrete, Stone, Glass, Wood, Metal };
constexpr int kWallMaterialCount = 7;
enum class RoofMaterial : uint8_t { RoofTiles = 0, Slate, Metal, Copper, Concrete, TarPaper, Thatch, Glass, Grass };
constexpr int kRoofMaterialCount = 9;
const char* to_string(WallMaterial material);
const char* to_string(RoofMaterial material);

constexpr uint8_t kWallColourInferred = 1, kRoofColourInferred = 2;

struct Building {
    OsmRef osm;
    Ring outer;               // CCW
    std::vector<Ring> holes;  // CW
    double min_height = 0;
    double height = 0;
    int levels = 0;
    HeightSource height_source = HeightSource::Random;
    std::string type;
    bool is_part = false;
    // Format 1.1.
    RoofShape roof_shape = RoofShape::Flat;
    double roof_height = 0;           // eaves (top of the walls) = height - roof_height
    bool roof_inferred = false;
    std::vector<RoofFace> roof_faces{};  // empty: a flat roof at `height`
    HeightRule height_rule = HeightRule::Tagged;
    uint32_t wall_colour = 0, roof_colour = 0;  // sRGB 0xFFRRGGBB, 0 = none (stock colour)
    uint8_t colour_inferred = 0;      // kWallColourInferred | kRoofColourInferred
    WallMaterial wall_material = WallMaterial::Plaster;
    RoofMaterial roof_material = RoofMaterial::RoofTiles;
    bool generated = false;           // --fill-empty-blocks: not in the map

    double eaves_height() const { return height - roof_height; }
};

// Whether a building has anything to draw (a ring, a top above its bottom): the one test of
// both geometry modes, the render memory estimate, the lights and the roofs.
inline bool has_volume(const Building& b) { return b.outer.size() >= 3 && b.height > b.min_height; }

enum class RoadClass : uint8_t {
    Motorway = 0, Trunk, Primary, Secondary, Tertiary, Unclassified,
    Residential, LivingStreet, Service, Other
};
const char* to_string(RoadClass c);  // the highway value, e.g. "living_street"; "other"

enum class CentreLine : uint8_t { None = 0, Dashed, Solid, Double };

struct RoadEdge {
    OsmRef osm;
    int64_t from_node = 0, to_node = 0;
    std::vector<Vec2> centreline;
    Ring quad;                // 4 points CCW
    double width = 0;
    RoadClass road_class = RoadClass::Other;
    int lanes = 0;
    bool oneway = false;
    bool bridge = false;
    int from_joint = -1, to_joint = -1;
    bool sidewalk_left = false, sidewalk_right = false;
    // Format 1.1: the lane layout markings are painted from.
    int lanes_forward = 0, lanes_backward = 0;
    CentreLine centre_line = CentreLine::None;
    bool edge_lines = false;
    bool cycle_lane_left = false, cycle_lane_right = false;  // painted cycle lanes at the edges
};

struct Joint {
    OsmRef osm;
    Ring polygon;             // CCW
    std::vector<uint32_t> edges;
};

enum class SidewalkKind : uint8_t { Strip = 0, Corner = 1 };

struct Sidewalk {
    SidewalkKind kind = SidewalkKind::Strip;
    Ring polygon;             // CCW
    int road = -1;
    int joint = -1;
    double curb_height = 0.15;
};

enum class LampSource : uint8_t { Tagged = 0, Generated = 1 };

struct Lamp {
    OsmRef osm;
    Vec3 position;
    double height = 6;
    LampSource source = LampSource::Tagged;
};

struct Ground {
    Vec2 min, max;
    double z = 0;
};

// Land cover classes, in the schema's order (schema/scene.fbs).
enum class LandCoverClass : uint8_t { Water = 0, Sea, Green, Forest, Paved, Sand, Farmland, BuiltUp };
constexpr int kLandCoverClassCount = 8;
const char* to_string(LandCoverClass c);  // "water", "sea", ...

// Where classes overlap, the one with the higher priority is seen: render draws each class
// at its own small height in this order (0 lowest), so nothing z-fights and nothing shows
// twice. Water lies on everything, paved open space on green, green on forest and farmland,
// the sea above built-up land use (a harbour's landuse polygon often reaches into the
// basin), built-up paving lowest. The one definition; README "Land cover" documents it.
inline int land_cover_priority(LandCoverClass c) {
    switch (c) {
        case LandCoverClass::BuiltUp: return 0;
        case LandCoverClass::Farmland: return 1;
        case LandCoverClass::Sea: return 2;
        case LandCoverClass::Forest: return 3;
        case LandCoverClass::Green: return 4;
        case LandCoverClass::Sand: return 5;
        case LandCoverClass::Paved: return 6;
        case LandCoverClass::Water: return 7;
    }
    return 0;
}

struct LandCover {
    OsmRef osm;
    LandCoverClass cover = LandCoverClass::Green;
    Ring outer;               // CCW
    std::vector<Ring> holes;  // CW
};

enum class LeafType : uint8_t { Broadleaved = 0, Needleleaved = 1 };
enum class TreeSource : uint8_t { Mapped = 0, Row = 1, Scattered = 2 };
const char* to_string(TreeSource s);  // "mapped", "row", "scattered"

struct Tree {
    OsmRef osm;
    Vec2 position;
    double height = 10;          // ground to crown top
    double crown_diameter = 6;
    LeafType leaf_type = LeafType::Broadleaved;
    TreeSource source = TreeSource::Mapped;
};

enum class PathClass : uint8_t {
    Footway = 0, Path, Cycleway, Pedestrian, Steps, Track, Bridleway, Rail, Tram, LightRail, Subway
};
constexpr int kPathClassCount = 11;
const char* to_string(PathClass c);  // "footway", ..., "light_rail", "subway"
inline bool is_rail(PathClass c) { return c >= PathClass::Rail; }

struct PathEdge {
    OsmRef osm;
    int64_t from_node = 0, to_node = 0;
    std::vector<Vec2> centreline;
    Ring quad;                // 4 points CCW
    double width = 0;
    PathClass path_class = PathClass::Footway;
    int from_joint = -1, to_joint = -1;  // into Scene::path_joints
    bool sidewalk = false;
    bool bridge = false;  // set only with a height field (osmparse --dem)
};

enum class CrossingKind : uint8_t { Zebra = 0, StopLine = 1 };
enum class RoadSide : uint8_t { Both = 0, Left = 1, Right = 2 };

struct Crossing {
    OsmRef osm;
    int road = -1;
    Vec2 position;
    CrossingKind kind = CrossingKind::Zebra;
    RoadSide side = RoadSide::Both;
};

// Format 1.2: the ground's heights, from a DEM (osmparse --dem); empty without one. A regular
// grid of nodes over the scene's bounds: node (i, j) at origin + (i * cell, j * cell), heights
// row-major (i fastest, rows south to north) in metres above reference_altitude, which is in
// metres above vertical_datum (e.g. "EGM96 geoid", SRTM's). docs/terrain.md.
struct HeightField {
    Vec2 origin;
    double cell = 0;
    uint32_t nx = 0, ny = 0;
    std::vector<float> heights;
    double reference_altitude = 0;
    std::string vertical_datum;

    bool empty() const { return heights.empty(); }
    // The height at (x, y) above reference_altitude: bilinear between the 4 nodes around it,
    // clamped to the grid's edge outside it; 0 for an empty field.
    double at(double x, double y) const;
};

// Format 1.2: a mapped retaining wall (barrier=retaining_wall), kept only with a height field
// (osmparse --dem). OSM's convention: the ground is lower on the right of the way's direction.
// docs/terrain.md, "Retaining walls".
struct RetainingWall {
    OsmRef osm;
    std::vector<Vec2> line;   // the way's direction; a closed way repeats its first point
    double height = 0;        // low side's ground to the high side's
    bool height_tagged = false;
    WallMaterial material = WallMaterial::Concrete;
};

struct SceneHeader {
    uint16_t format_major = kSceneFormatMajor;
    uint16_t format_minor = kSceneFormatMinor;
    std::string generator;
    double origin_lat = 0, origin_lon = 0;
    std::string projection;
    Vec2 bounds_min, bounds_max;
    uint64_t seed = 0;
    std::vector<std::pair<std::string, std::string>> options;  // sorted by key
    std::string source;
};

struct Scene {
    SceneHeader header;
    std::vector<Building> buildings;
    std::vector<RoadEdge> roads;
    std::vector<Joint> joints;
    std::vector<Sidewalk> sidewalks;
    std::vector<Lamp> lamps;
    Ground ground;
    std::vector<LandCover> land_cover;  // format 1.1
    std::vector<Tree> trees;            // format 1.1
    std::vector<PathEdge> paths;        // format 1.1
    std::vector<Joint> path_joints;     // format 1.1; edges index into paths
    std::vector<Crossing> crossings;    // format 1.1
    HeightField terrain;                // format 1.2
    std::vector<RetainingWall> retaining_walls;  // format 1.2, with the terrain only
};

}  // namespace citygen
