// Stage 1: read an OSM file (.osm, .osm.gz, .osm.bz2, .osm.pbf) into OsmData.
#pragma once

#include <string>

#include "osmparse/core/osm_data.h"
#include "osmparse/core/report.h"

namespace citygen {

// Throws citygen::Error with one line naming the file for missing, empty, truncated,
// malformed or non-OSM input. Objects the extract cuts off (ways with missing nodes,
// relations with missing members, broken polygons) are skipped or clipped and counted.
// Reads the file once (see read_osm.cpp).
OsmData read_osm(const std::string& path, bool quiet, ParseReport& report);

}  // namespace citygen
