// Stage 14, with land cover: the sea. OSM has no sea polygons, only natural=coastline ways with the land on their left
// (water on the right). As osmcoastline does, the coastline is joined into chains, clipped
// to the extract's bounds and closed along the bounds' edge into water polygons; closed
// coastline rings inside the bounds are islands (holes) or enclosed seas.
#pragma once

#include <utility>
#include <vector>

#include "common/scene.h"
#include "osmparse/core/osm_data.h"
#include "common/projection.h"
#include "osmparse/core/report.h"

namespace citygen {

// The rectangle (local metres) the sea is clipped to: the file header's bounds when given,
// else the bounds of the data read.
Box2 extract_box(const OsmData& osm, const Projection& projection);
// The same bounds in degrees (min, max).
std::pair<LatLon, LatLon> extract_bounds(const OsmData& osm);

// Sea polygons (class Sea, outer CCW, holes CW) inside `box`. A chain cut short by a
// clipped extract (its next node missing) is carried to the nearest box edge, counted.
// Coastline that cannot be closed consistently (a chain ending inside the box without being
// cut there, pieces whose directions disagree along the edge) gives no sea at all, counted
// under "sea polygons": never a flooded city. `buildings` guard the result too: a sea polygon holding more than half of them
// (at least 10) is taken for land and dropped. Sorted by OSM identity of its first way.
std::vector<LandCover> assemble_sea(const OsmData& osm, const Projection& projection, const Box2& box,
                                    const std::vector<Building>& buildings, ParseReport& report);

// The geometric core, for tests: coastline chains (local metres, land on the left; closed
// chains repeat their first point at the end) with their way ids -> sea polygons.
struct CoastlineChain {
    std::vector<Vec2> points;
    int64_t way_id = 0;
    // The chain goes on beyond its first / last point through nodes missing from a clipped
    // extract: an end inside the box is then carried straight to the nearest box edge.
    bool cut_before = false, cut_after = false;
};
std::vector<LandCover> sea_from_chains(const std::vector<CoastlineChain>& chains, const Box2& box,
                                       ParseReport& report);

}  // namespace citygen
