// Bridges that are mapped only by `layer` (issue 22, item 5): OSM's layer orders what crosses, so a
// road, path or rail with layer > 0 that crosses a drawn way of a lower layer, or water, stands on
// a structure even without a bridge tag. Only with a height field, where a bridge gets its own
// deck (common/bridge_deck.h); flat scenes keep their bytes.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "common/scene.h"
#include "osmparse/core/osm_data.h"
#include "osmparse/core/report.h"

namespace citygen {

// The layer of every highway and railway way that has a nonzero whole `layer` (-5..5, OSM's range);
// ways not in the map are at layer 0.
std::unordered_map<int64_t, int> way_layers(const OsmData& osm);

// Marks as bridges the edges with layer > 0 and no bridge tag whose centreline properly crosses
// a road's or path's centreline of a lower layer, or a water or sea polygon's outline, or lies
// inside one; counted in the report.
void mark_layered_bridges(std::vector<RoadEdge>& roads, std::vector<PathEdge>& paths,
                          const std::unordered_map<int64_t, int>& layers, const std::vector<LandCover>& land_cover,
                          ParseReport& report);

}  // namespace citygen
