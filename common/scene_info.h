// A scene file's summary for people and scripts (`key: value` lines): `osmparse --info` and
// `render --print-scene-info` print the same.
#pragma once

#include <cstdio>
#include <string>

#include "common/scene.h"

namespace citygen {

// Counts per object kind, bounds, origin, format version and parse options; `name` is the
// file the scene came from.
void print_scene_info(const Scene& scene, const std::string& name, std::FILE* out);

}  // namespace citygen
