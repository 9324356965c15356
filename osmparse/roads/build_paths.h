// Stage 11: paths and rails. highway=footway|path|cycleway|pedestrian|steps|track|bridleway and
// railway=rail|tram|light_rail|subway ways (not in tunnels, not areas) as strips laid out
// with the road join rules (road_layout.h), without curbs. Paths and rails are laid out as
// two separate networks, so a level crossing of a footway over a track makes no joint.
#pragma once

#include <optional>
#include <vector>

#include "common/scene.h"
#include "osmparse/core/osm_data.h"
#include "osmparse/core/params.h"
#include "common/projection.h"
#include "osmparse/core/report.h"

namespace citygen {

// The path class of a way's tags, or nullopt. highway=pedestrian as a line (a pedestrian
// street) is a path; as an area it is land cover.
std::optional<PathClass> path_class_of(const OsmTags& tags);

// The report row that counts the kept paths of a class ("path: footway", ...).
ReportKind path_class_row(PathClass c);

// Width from `width` (1 to 20 m), else the class table: footway 2, path 1.5, cycleway 2,
// pedestrian 5, steps 2, track 3, bridleway 2, rail 3, tram 2.6, light_rail 3, subway 3 m.
double path_width(const OsmTags& tags, PathClass c, ParseReport* report);

struct PathSurface {
    std::vector<PathEdge> paths;
    std::vector<Joint> joints;  // edges index into paths
};

// Keeps of `highways` only what build_paths reads: the ways with a path class, with the tags
// it reads (highway, railway, tunnel, area, indoor, width, footway, bridge, covered), in their order. The
// road stages read every highway first; the paths run after them (see pipeline.cpp).
void keep_path_ways(std::vector<OsmWay>& highways);

// `with_terrain` (osmparse --dem): paths tagged bridge=* are marked to keep their own deck, which
// only a height field gives them (without one the scene stays as it was before decks), and the
// covered ones (is_covered) are counted, a note under "path ways".
PathSurface build_paths(const OsmData& osm, const Projection& projection, const RoadParams& roads,
                        bool with_terrain, ParseReport& report);

// Mapped sidewalks (footway=sidewalk) replace ours: a generated sidewalk piece that a mapped
// one, widened by 2.5 m to each side (mapped sidewalks lie a little off where ours are),
// covers by more than a third of its area is dropped (counted), so nothing is doubled.
std::vector<Sidewalk> drop_doubled_sidewalks(std::vector<Sidewalk> sidewalks, const std::vector<PathEdge>& paths,
                                             ParseReport& report);

}  // namespace citygen
