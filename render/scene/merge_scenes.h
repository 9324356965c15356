// Several scenes loaded as one city: the tiles of a region parsed on the farm
// (scripts/farm/parse_farm.sh, docs/farm.md) in one shared frame, each object kept by one tile.
#pragma once

#include <string>
#include <vector>

#include "common/scene.h"

namespace citygen {

// One path: load_scene's scene, untouched. Several: merge_scenes of them in the order given.
Scene load_scenes(const std::vector<std::string>& paths);

// The scenes' lists (retaining walls too) one after another, every index between lists (an edge's joints, a joint's
// edges, a sidewalk's road and joint, a crossing's road) moved with them; an edge end a tile cut
// from its joint (osmparse --keep-inside) is linked again to the joint at its node. Bounds and
// ground cover them all. Tiles parsed with --dem have their fields joined into one (each node
// from the tile it lies deepest inside, merge_scenes.cpp). Throws Error, naming the file by
// `names`, when the scenes do not share a frame (origin, projection), a seed (the facades follow
// it) or, with terrain, its node spacing and datum; or when some have terrain and some not.
Scene merge_scenes(std::vector<Scene> scenes, const std::vector<std::string>& names);

}  // namespace citygen
