// What kinds of scene objects the renderer knows, and how each class is turned into geometry.
#pragma once

#include <array>
#include <cstdint>
#include <string>

namespace citygen {

// The object classes of a scene file; a hit reports one of these plus the object's index in the
// scene file's list of that class, whatever geometry mode produced it.
enum class ObjectKind : uint8_t {
    None = 0, Building, Road, Joint, Sidewalk, Terrain, Lamp, LandCover, Tree, Path, PathJoint, RetainingWall
};
constexpr int kObjectKindCount = 12;

const char* to_string(ObjectKind kind);  // "building", "road", ...

// Stored: every triangle built up front (RTC_GEOMETRY_TYPE_TRIANGLE).
// Procedural: only outlines kept, surfaces computed inside Embree user-geometry callbacks.
enum class GeometryMode : uint8_t { Stored = 0, Procedural = 1 };

const char* to_string(GeometryMode mode);  // "stored" / "procedural"
// Throws citygen::Error for anything but "stored" or "procedural".
GeometryMode parse_geometry_mode(const std::string& text, const std::string& option_name);

// The classes that have a selectable geometry mode.
enum class GeometryClass : uint8_t {
    Buildings = 0, Roads, Joints, Sidewalks, Terrain, LandCover, Trees, Paths, Lamps, RetainingWalls
};
constexpr int kGeometryClassCount = 10;
const char* to_string(GeometryClass c);  // "buildings", "roads", ...

struct GeometryModes {
    std::array<GeometryMode, kGeometryClassCount> mode{};  // all Stored
    GeometryMode& operator[](GeometryClass c) { return mode[static_cast<int>(c)]; }
    GeometryMode operator[](GeometryClass c) const { return mode[static_cast<int>(c)]; }
    static GeometryModes all(GeometryMode m) { GeometryModes g; g.mode.fill(m); return g; }
};

}  // namespace citygen
