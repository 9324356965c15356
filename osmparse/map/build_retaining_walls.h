// Retaining walls (issue 22): barrier=retaining_wall ways -> the scene's RetainingWall lines, in
// local metres, with their height and material. Kept only with a height field (osmparse --dem):
// on the flat ground a wall has no step to stand in, and the scene stays what it was.
// docs/terrain.md, "Retaining walls".
#pragma once

#include <vector>

#include "common/projection.h"
#include "common/scene.h"
#include "osmparse/core/osm_data.h"
#include "osmparse/core/report.h"

namespace citygen {

// The height of a wall whose `height` is untagged or unusable (metres). Neither Monaco's 37 nor
// Malta's 50 mapped retaining walls tag one, so this is most walls' height: a terrace or garden
// wall of a hillside town stands 1 to 3 m. It is the least step the field is given (where the
// DEM falls further at the wall it is kept, fit in retaining_wall_steps.h), so a taller wall
// left untagged still stands in its real step wherever the DEM resolves it.
constexpr double kDefaultRetainingWallHeight = 2;

// One wall per run of present nodes (a way clipped by the extract may give several), its line
// in the way's direction with repeated points removed; `height` (any unit parse_osm_length
// knows, in (0, kMaxHeight]) else the default; `material` as building:material is read
// (concrete, stone, brick, ...), else concrete. Counted under ReportKind::RetainingWalls: read
// (ways), kept (walls), dropped (nodes missing, zero length, beyond the scene limits), notes
// (clipped at the extract's edge, the height defaulted).
std::vector<RetainingWall> build_retaining_walls(const OsmData& osm, const Projection& projection, ParseReport& report);

}  // namespace citygen
