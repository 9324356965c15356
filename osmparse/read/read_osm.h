// Stage 1: read an OSM file (.osm, .osm.gz, .osm.bz2, .osm.pbf) into OsmData.
#pragma once

#include <string>

#include "osmparse/core/osm_data.h"
#include "osmparse/core/report.h"

namespace citygen {

// Report rows of the read stage (read_osm_handlers.h); later stages add to some of them.
inline constexpr char kMappedTrees[] = "mapped trees";
inline constexpr char kRoadMarkNodes[] = "crossing and signal nodes";
inline constexpr char kTaggedStreetLamps[] = "tagged street lamps";
inline constexpr char kHighwayWays[] = "highway ways";
inline constexpr char kCoastlineWays[] = "coastline ways";
inline constexpr char kTreeRows[] = "tree rows";
inline constexpr char kRailwayWays[] = "railway ways";
inline constexpr char kBuildingWays[] = "building ways";
inline constexpr char kBuildingRelations[] = "building relations";
inline constexpr char kBuildingAreas[] = "building areas";
inline constexpr char kLandCoverAreas[] = "land cover areas";
// Reasons.
inline constexpr char kInvalidLocation[] = "invalid location";
inline constexpr char kNodesMissing[] = "nodes missing from extract";
inline constexpr char kClippedAtEdge[] = "clipped at extract edge";
inline constexpr char kNotClosed[] = "not closed";
inline constexpr char kOutlinePassedForRepair[] = "invalid outline passed on for repair";
inline constexpr char kCouldNotAssemble[] = "invalid multipolygon (could not assemble)";
inline constexpr char kMembersMissing[] = "members missing from extract";
inline constexpr char kRelationMembersMissing[] = "relation members missing from extract";

// Throws citygen::Error with one line naming the file for missing, empty, truncated,
// malformed or non-OSM input. Objects the extract cuts off (ways with missing nodes,
// relations with missing members, broken polygons) are skipped or clipped and counted.
// Reads the file once (see read_osm.cpp).
OsmData read_osm(const std::string& path, bool quiet, ParseReport& report);

}  // namespace citygen
