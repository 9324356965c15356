// `osmparse --diff`: two scene files compared object by object.
#pragma once

#include <string>
#include <vector>

#include "common/scene.h"

namespace citygen {

// One difference between two scenes, e.g. {"moved", "building w123 #0", "outer ring moved 0.8 m"}.
struct SceneChange {
    std::string what;    // "added", "removed" or "changed"
    std::string object;  // kind + OSM identity, e.g. "building w123#0"
    std::string detail;
};

// Compares scenes object by object, matched by OSM identity. Geometry that moved by at
// most `tolerance` metres (and heights within it) counts as equal. Header fields other
// than the format version and options are ignored: they follow from the objects.
std::vector<SceneChange> diff_scenes(const Scene& a, const Scene& b, double tolerance);

}  // namespace citygen
