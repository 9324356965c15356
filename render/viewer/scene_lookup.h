// What the viewer tells about the scene: the object under a picked pixel (its kind, OSM id and
// what the scene file keeps of it), a top-down map of it, and where an OSM id or a lat,lon is.
// Answers are JSON texts.
#pragma once

#include <optional>
#include <string>

#include "common/scene.h"
#include "render/scene/hit.h"

namespace citygen {

// {"kind": "building", "osm": "w123", "osm_type": "way", "osm_id": 123, "index": 4, "fields": {...}}
// or {"kind": "sky"} for no hit.
std::string describe_hit(const Scene& scene, bool hit, const Hit& at);

// {"bounds": {"min": [x, y], "max": [x, y]}, "buildings": [[x0, y0, x1, y1, ...], ...],
//  "roads": [[...]], "water": [[...]]}, metres rounded to 0.1.
std::string scene_map_json(const Scene& scene);

// Where to look for "w123" / "n5" / "r7" (an object's centre, on the ground, and its radius)
// or "lat,lon" (which must lie within 50 km of the scene); nullopt with `why` set otherwise.
struct Place {
    Vec3 centre;
    double radius = 0;
};
std::optional<Place> find_place(const Scene& scene, const std::string& query, std::string& why);

}  // namespace citygen
