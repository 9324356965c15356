// Stage 15: trees. natural=tree nodes, natural=tree_row ways (spaced along the way) and forests
// (land cover class Forest) filled with a seeded Poisson-disk scatter.
#pragma once

#include <vector>

#include "common/scene.h"
#include "osmparse/core/osm_data.h"
#include "osmparse/core/params.h"
#include "common/projection.h"
#include "osmparse/core/report.h"

namespace citygen {

// Size of a tree from its tags: height from `height`, else `est_height`; crown from
// `diameter_crown`; leaf type from `leaf_type` (needleleaved, else broadleaved). Missing or
// absurd values (height outside [1, 80] m, crown outside [0.5, 40] m) fall back to the
// defaults of the leaf type (broadleaved 10 m high, crown 7 m; needleleaved 14 m, crown
// 5 m) and are noted in `report` under `kind`.
Tree tree_from_tags(const OsmTags& tags, ParseReport& report, ReportKind kind);

// Every tree of the scene, in order: mapped, rows, scattered. No tree stands in a building,
// on a road or joint, or in water; a mapped tree on our (often wider than mapped) road
// surface is moved just off it, one in a building or in water is dropped. Row and forest
// trees also keep off paths and rails. Scattered trees
// keep params.forest_spacing from each other, the seed decides where. Uses the scene's
// buildings, roads, joints, paths and land cover.
std::vector<Tree> place_trees(const OsmData& osm, const Projection& projection, const Scene& scene,
                              const TreeParams& params, uint64_t seed, ParseReport& report);

}  // namespace citygen
