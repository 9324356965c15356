// --export-ply: every stored triangle of the render scene as one binary little-endian PLY with
// a per-face material index (MaterialId), for Blender, MeshLab or a Cycles comparison.
#pragma once

#include <string>

#include "render/materials/materials.h"
#include "render/scene/render_scene.h"

namespace citygen {

// The header carries one comment per material ("material ID NAME TYPE r g b sr sg sb EXPONENT
// IOR"), so a script can rebuild the materials without knowing our tables.
// Throws citygen::Error if a class is procedural (no triangles to export) or on write failure.
void export_ply(const RenderScene& scene, const MaterialTable& materials, const std::string& path);

}  // namespace citygen
