#include "build_render_scene.h"

#include <string>

#include "procedural_geometry.h"
#include "procedural_lamps.h"
#include "stored_geometry.h"

namespace citygen {

std::unique_ptr<RenderScene> build_render_scene(const Scene& scene, const GeometryModes& modes,
                                                const FacadeOptions& facades, const ProgressSettings& progress) {
    auto render_scene = std::make_unique<RenderScene>();
    // Buildings are nearly all of the work (every facade triangle), so they measure it.
    Progress geometry_progress("geometry", scene.buildings.size(), progress);
    auto stored = [](TriangleMesh mesh) { return std::make_unique<StoredMeshGeometry>(std::move(mesh)); };
    auto procedural = [&](GeometryClass c) { return modes[c] == GeometryMode::Procedural; };
    if (procedural(GeometryClass::Buildings)) render_scene->add(build_procedural_buildings(scene, facades, &geometry_progress));
    else render_scene->add(stored(build_stored_buildings(scene, facades, &geometry_progress)));
    if (procedural(GeometryClass::Terrain)) render_scene->add(build_procedural_terrain(scene));
    else render_scene->add(stored(build_stored_terrain(scene)));
    if (procedural(GeometryClass::Roads)) render_scene->add(build_procedural_roads(scene));
    else render_scene->add(stored(build_stored_roads(scene)));
    if (procedural(GeometryClass::Joints)) render_scene->add(build_procedural_joints(scene));
    else render_scene->add(stored(build_stored_joints(scene)));
    if (procedural(GeometryClass::Sidewalks)) render_scene->add(build_procedural_sidewalks(scene));
    else render_scene->add(stored(build_stored_sidewalks(scene)));
    if (procedural(GeometryClass::Lamps)) render_scene->add(build_procedural_lamps(scene));
    else render_scene->add(stored(build_stored_lamps(scene)));
    geometry_progress.finish();
    render_scene->commit(progress);
    return render_scene;
}

}  // namespace citygen
