// Small scenes built in code for tests of all three libraries.
#pragma once

#include "common/scene.h"

namespace citygen::test {

// An axis-aligned box building (way 1) from (x0, y0) to (x1, y1).
inline Building box_building(double x0, double y0, double x1, double y1, double height = 10) {
    Building b;
    b.osm = {OsmType::Way, 1};
    b.outer = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
    b.height = height;
    return b;
}

// A scene of that one building on a 200 x 200 m ground.
inline Scene scene_with(const Building& b) {
    Scene s;
    s.buildings.push_back(b);
    s.ground.min = {-100, -100};
    s.ground.max = {100, 100};
    return s;
}

// The first road edge of OSM way `way`, or null.
inline const RoadEdge* road_of_way(const Scene& s, int64_t way) {
    for (const RoadEdge& r : s.roads)
        if (r.osm.id == way) return &r;
    return nullptr;
}

}  // namespace citygen::test
