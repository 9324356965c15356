// Limits on scene geometry that no real city reaches. osmparse drops (and counts) objects
// beyond them; decode_scene refuses a file that holds any, so the renderer's cost stays
// bounded by the file's size and never by the values inside it. Documented in README.md.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/geometry.h"

namespace citygen {

// Any x, y (and z) of a scene point, metres from the origin: 1000 km. float32 still resolves
// 6 cm there; a city extract spans a few tens of km.
constexpr double kMaxCoordinate = 1e6;
// Bounding box side of one building ring, road edge, joint or sidewalk piece, metres.
constexpr double kMaxObjectExtent = 10000;
// Building heights and lamp heights, metres above the ground (the tallest building is 828 m).
constexpr double kMaxHeight = 1000;
// Points in one ring or polygon (an OSM way has at most 2000 nodes).
constexpr size_t kMaxRingPoints = 10000;

// Land cover (the sea, a forest) may span a whole region: its own, looser limits on one
// polygon's points and size (a coastline of a large extract has many points; the procedural
// mode's tiling costs about points^2 / 32, a second or two at this limit).
constexpr size_t kMaxLandCoverPoints = 100000;
constexpr double kMaxLandCoverExtent = 2 * kMaxCoordinate;

// The terrain's height field (format 1.2). Ground altitudes, metres above sea level: the Dead
// Sea's shore is at -430 m, Everest 8,849 m; a DEM's value beyond them is a void (no data).
constexpr double kMinAltitude = -500, kMaxAltitude = 9000;
// Nodes in one height field: 268 MB of heights, 8 x 8 km at 1 m, a whole region at 30 m.
constexpr uint64_t kMaxHeightFieldNodes = uint64_t(1) << 26;

// The checks themselves, on a value as the scene stores it (float32): decode_scene refuses
// what fails them, and osmparse drops or clips it before writing with these same functions.
// A coordinate within `limit` of the origin (and finite).
inline bool coordinate_within_limit(double v, double limit = kMaxCoordinate) {
    // Compared as a double first: a double beyond float's range has no float value.
    return std::fabs(v) <= 2 * limit && std::fabs(static_cast<float>(v)) <= limit;
}
inline bool point_within_limit(Vec2 p, double limit = kMaxCoordinate) {
    return coordinate_within_limit(p.x, limit) && coordinate_within_limit(p.y, limit);
}
// One object's points, as stored, fit in a `max_extent` square.
inline bool extent_within_limit(const std::vector<Vec2>& points, double max_extent = kMaxObjectExtent) {
    Box2 box;
    for (Vec2 p : points) box.extend({static_cast<float>(p.x), static_cast<float>(p.y)});
    return box.empty() || std::max(box.max.x - box.min.x, box.max.y - box.min.y) <= max_extent;
}

// An altitude within kMinAltitude..kMaxAltitude (NaN is not).
inline bool altitude_within_limit(double altitude) { return altitude >= kMinAltitude && altitude <= kMaxAltitude; }
// A height field's grid: at least 2 x 2 nodes and at most kMaxHeightFieldNodes, a positive
// cell, and its corners within the coordinate limit.
inline bool height_field_within_limit(Vec2 origin, double cell, uint64_t nx, uint64_t ny) {
    if (nx < 2 || ny < 2 || nx > kMaxHeightFieldNodes / ny || !(cell > 0) || !std::isfinite(cell)) return false;
    const Vec2 far_corner = origin + Vec2((nx - 1) * cell, (ny - 1) * cell);
    return point_within_limit(origin) && point_within_limit(far_corner);
}

}  // namespace citygen
