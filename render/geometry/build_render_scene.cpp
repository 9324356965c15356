#include "render/geometry/build_render_scene.h"

#include <string>

#include "render/geometry/land_cover_geometry.h"
#include "render/geometry/path_geometry.h"
#include "render/geometry/procedural_geometry.h"
#include "render/geometry/procedural_lamps.h"
#include "render/geometry/road_markings.h"
#include "render/geometry/stored_geometry.h"
#include "render/geometry/terrain_geometry.h"
#include "render/geometry/tree_geometry.h"

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
    if (procedural(GeometryClass::Terrain) && !scene.terrain.empty())
        render_scene->add(build_procedural_field_terrain(scene));
    else if (procedural(GeometryClass::Terrain)) render_scene->add(build_procedural_terrain(scene));
    else render_scene->add(stored(build_stored_terrain(scene)));
    // Markings and asphalt grain are painted at shading time (road_markings.h), in both modes.
    if (procedural(GeometryClass::Roads)) render_scene->add(with_road_markings(build_procedural_roads(scene), scene));
    else render_scene->add(with_road_markings(stored(build_stored_roads(scene)), scene));
    if (procedural(GeometryClass::Joints)) render_scene->add(with_asphalt_grain(build_procedural_joints(scene)));
    else render_scene->add(with_asphalt_grain(stored(build_stored_joints(scene))));
    if (procedural(GeometryClass::Sidewalks)) render_scene->add(build_procedural_sidewalks(scene));
    else render_scene->add(stored(build_stored_sidewalks(scene)));
    // The map beyond roads (format 1.1); empty classes add no geometry.
    if (!scene.land_cover.empty()) {
        if (procedural(GeometryClass::LandCover)) render_scene->add(with_water_waves(build_procedural_land_cover(scene)));
        else render_scene->add(with_water_waves(stored(build_stored_land_cover(scene))));
    }
    if (!scene.paths.empty()) {
        if (procedural(GeometryClass::Paths)) {
            render_scene->add(with_rail_tracks(build_procedural_paths(scene), scene));
            if (!scene.path_joints.empty()) render_scene->add(build_procedural_path_joints(scene));
        } else {
            render_scene->add(with_rail_tracks(stored(build_stored_paths(scene)), scene));
            if (!scene.path_joints.empty()) render_scene->add(stored(build_stored_path_joints(scene)));
        }
    }
    if (!scene.trees.empty()) {
        if (procedural(GeometryClass::Trees)) render_scene->add(build_procedural_trees(scene));
        else render_scene->add(build_stored_trees(scene));
    }
    if (procedural(GeometryClass::Lamps)) render_scene->add(build_procedural_lamps(scene));
    else render_scene->add(stored(build_stored_lamps(scene)));
    geometry_progress.finish();
    render_scene->commit(progress);
    return render_scene;
}

}  // namespace citygen
