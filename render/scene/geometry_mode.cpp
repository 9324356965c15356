#include "render/scene/geometry_mode.h"

#include "common/error.h"

namespace citygen {

const char* to_string(ObjectKind kind) {
    switch (kind) {
        case ObjectKind::None: return "none";
        case ObjectKind::Building: return "building";
        case ObjectKind::Road: return "road";
        case ObjectKind::Joint: return "joint";
        case ObjectKind::Sidewalk: return "sidewalk";
        case ObjectKind::Terrain: return "terrain";
        case ObjectKind::Lamp: return "lamp";
        case ObjectKind::LandCover: return "land_cover";
        case ObjectKind::Tree: return "tree";
        case ObjectKind::Path: return "path";
        case ObjectKind::PathJoint: return "path_joint";
        case ObjectKind::RetainingWall: return "retaining_wall";
    }
    return "?";
}

const char* to_string(GeometryMode mode) {
    return mode == GeometryMode::Stored ? "stored" : "procedural";
}

GeometryMode parse_geometry_mode(const std::string& text, const std::string& option_name) {
    if (text == "stored") return GeometryMode::Stored;
    if (text == "procedural") return GeometryMode::Procedural;
    throw Error(option_name + ": expected 'stored' or 'procedural', got '" + text + "'");
}

const char* to_string(GeometryClass c) {
    switch (c) {
        case GeometryClass::Buildings: return "buildings";
        case GeometryClass::Roads: return "roads";
        case GeometryClass::Joints: return "joints";
        case GeometryClass::Sidewalks: return "sidewalks";
        case GeometryClass::Terrain: return "terrain";
        case GeometryClass::LandCover: return "land-cover";
        case GeometryClass::Trees: return "trees";
        case GeometryClass::Paths: return "paths";
        case GeometryClass::Lamps: return "lamps";
        case GeometryClass::RetainingWalls: return "retaining-walls";
    }
    return "?";
}

}  // namespace citygen
