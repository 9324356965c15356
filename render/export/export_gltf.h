// --export-gltf: the stored geometry as one binary glTF 2.0 file (.glb) for Blender and other
// tools: one node per building (named "building w123", its OSM reference in extras.osm_id and
// its height in extras.height_m), one node per other class (roads, joints, sidewalks, terrain,
// lamps), a primitive per material, metallic-roughness PBR materials (emission for glowing
// ones, KHR_materials_transmission for glass). Metres; citygen's z-up turned into glTF's y-up
// (x, y, z) -> (x, z, -y). No normals: every face is flat, which viewers compute themselves.
#pragma once

#include <string>

#include "common/scene.h"
#include "render/materials/materials.h"
#include "render/scene/render_scene.h"

namespace citygen {

// Throws citygen::Error if a class is procedural (no triangles to export) or on write failure.
// Writes atomically (a temporary beside `path`, then renamed).
void export_gltf(const Scene& scene, const RenderScene& render_scene, const MaterialTable& materials,
                 const std::string& path);

}  // namespace citygen
