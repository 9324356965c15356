// --export-ply: every stored triangle of the render scene as one binary little-endian PLY with
// a per-face material index (MaterialId), for Blender, MeshLab or a Cycles comparison.
#pragma once

#include <string>

#include "render_scene.h"

namespace citygen {

// Throws citygen::Error if a class is procedural (no triangles to export) or on write failure.
void export_ply(const RenderScene& scene, const std::string& path);

}  // namespace citygen
