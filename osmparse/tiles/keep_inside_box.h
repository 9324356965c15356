// One tile of a region parsed on the farm (scripts/farm/parse_farm.sh, docs/farm.md). The tile's
// extract reaches beyond its core box by an overlap, so that whatever lies near the core's edge
// is parsed from the same data as in a parse of the whole region; then only the objects whose
// anchor lies in the core box are kept. The tiles' core boxes share their edges and are
// half-open, and an object parsed in two tiles is the same in both, so exactly one keeps it.
#pragma once

#include "common/projection.h"
#include "common/scene.h"
#include "osmparse/core/osm_data.h"
#include "osmparse/core/report.h"
#include "osmparse/tiles/lat_lon_text.h"

namespace citygen {

// The point that decides the tile of an object (scene metres).
Vec2 ring_anchor(const Ring& ring);          // area centroid; the box centre of a degenerate ring
Vec2 edge_anchor(const std::vector<Vec2>& centreline);  // the middle of its first and last point
// Whether `box` holds a point (in degrees, where the tiles' boxes meet exactly; the tiles share
// the projection, so an object's anchor is the same point in each).
bool box_holds(const LatLonBox& box, const Projection& projection, Vec2 point);

// The rectangle (scene metres) a tile's sea is assembled in: around the part of its core box
// within the extract of `osm`. The sea is no OSM object to anchor but what the coastline closes
// within a box, so each tile makes the sea of its core, and the tiles' seas together cover the
// region's. Lines of latitude and longitude are curves in the plane: the rectangle holds the
// core's edges, sampled, and a metre more, so neighbours' seas overlap (the same water) rather
// than leave a gap; it ends where the extract's box (extract_box) does, as one parse's sea.
Box2 tile_sea_box(const LatLonBox& core, const OsmData& osm, const Projection& projection);

// Drops every object whose anchor is outside `box` and renumbers the references between the
// rest. Sidewalks go with their corner's joint or their strip's road, crossings with their road,
// and a joint with its first edge (whose class a path joint's paving shows), so what refers to
// something keeps it (and every sea polygon stays: tile_sea_box); a reference to an object another tile keeps becomes -1 (an edge's joint)
// or is left out (a joint's edges): render's merge (render/scene/merge_scenes.h) links them again.
// Each dropped object is counted in the report's "tile:" rows. Returns how many of the first
// `leading` buildings stay (the pipeline's map buildings, before the generated ones).
size_t keep_inside_box(Scene& scene, const Projection& projection, const LatLonBox& box, ParseReport& report,
                       size_t leading = 0);

}  // namespace citygen
