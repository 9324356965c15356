// --print-memory-info, --print-scene-geometry-info (--print-scene-info: common/scene_info.h): some prose for people
// plus `key: value` lines for scripts (geometry_bytes:, peak_rss_bytes:, triangles:, ...).
#pragma once

#include <cstdio>

#include "common/scene.h"
#include "render/scene/render_scene.h"

namespace citygen {

void print_memory_info(const RenderScene& scene, FILE* out);
void print_geometry_info(const RenderScene& scene, FILE* out);

// Peak resident set size of this process (VmHWM), in bytes; 0 if unknown.
uint64_t peak_rss_bytes();

}  // namespace citygen
