// After the stages (--geojson): the scene back in WGS84 as a GeoJSON FeatureCollection, so a
// person can open it in QGIS or a web map. Every feature has `kind` (building, road,
// joint, sidewalk, lamp), `osm` ("w123", "n45", "r6") and what matters for that kind
// (width, height, source, ...). With a height field coordinates carry z (docs/terrain.md).
#pragma once

#include <string>

#include "common/scene.h"

namespace citygen {

std::string scene_to_geojson(const Scene& scene);

// Written atomically (temporary file + rename).
void write_geojson(const Scene& scene, const std::string& path);

}  // namespace citygen
