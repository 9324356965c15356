#include "render/geometry/build_render_scene.h"

#include <functional>
#ifdef __GLIBC__
#include <malloc.h>
#endif
#include <string>
#include <vector>

#include <tbb/parallel_for.h>

#include "render/geometry/land_cover_geometry.h"
#include "render/geometry/path_geometry.h"
#include "render/geometry/procedural_geometry.h"
#include "render/geometry/procedural_lamps.h"
#include "render/geometry/road_markings.h"
#include "render/geometry/stored_geometry.h"
#include "render/geometry/terrain_geometry.h"
#include "render/geometry/tree_geometry.h"
#include "render/geometry/wall_geometry.h"

namespace citygen {

namespace {

using Geometry = std::unique_ptr<RenderGeometry>;

// One builder per class, in the order of the Embree geometry ids, each in the class's mode.
std::vector<std::function<Geometry()>> class_builders(const Scene& scene, const GeometryModes& modes,
                                                      const FacadeOptions& facades, Progress& building_progress) {
    auto stored = [](TriangleMesh mesh) { return std::make_unique<StoredMeshGeometry>(std::move(mesh)); };
    auto procedural = [&modes](GeometryClass c) { return modes[c] == GeometryMode::Procedural; };
    std::vector<std::function<Geometry()>> builders;
    builders.push_back([&, stored, procedural]() -> Geometry {
        if (procedural(GeometryClass::Buildings)) return build_procedural_buildings(scene, facades, &building_progress);
        return stored(build_stored_buildings(scene, facades, &building_progress));
    });
    builders.push_back([&, stored, procedural]() -> Geometry {
        if (!procedural(GeometryClass::Terrain)) return stored(build_stored_terrain(scene));
        if (!scene.terrain.empty()) return build_procedural_field_terrain(scene);
        return build_procedural_terrain(scene);
    });
    // Markings and asphalt grain are painted at shading time (road_markings.h), in both modes.
    builders.push_back([&, stored, procedural]() -> Geometry {
        if (procedural(GeometryClass::Roads)) return with_road_markings(build_procedural_roads(scene), scene);
        return with_road_markings(stored(build_stored_roads(scene)), scene);
    });
    builders.push_back([&, stored, procedural]() -> Geometry {
        if (procedural(GeometryClass::Joints)) return with_asphalt_grain(build_procedural_joints(scene));
        return with_asphalt_grain(stored(build_stored_joints(scene)));
    });
    builders.push_back([&, stored, procedural]() -> Geometry {
        if (procedural(GeometryClass::Sidewalks)) return build_procedural_sidewalks(scene);
        return stored(build_stored_sidewalks(scene));
    });
    // The map beyond roads (format 1.1); empty classes add no geometry.
    if (!scene.land_cover.empty())
        builders.push_back([&, stored, procedural]() -> Geometry {
            if (procedural(GeometryClass::LandCover)) return with_water_waves(build_procedural_land_cover(scene));
            return with_water_waves(stored(build_stored_land_cover(scene)));
        });
    if (!scene.paths.empty()) {
        builders.push_back([&, stored, procedural]() -> Geometry {
            if (procedural(GeometryClass::Paths)) return with_rail_tracks(build_procedural_paths(scene), scene);
            return with_rail_tracks(stored(build_stored_paths(scene)), scene);
        });
        if (!scene.path_joints.empty())
            builders.push_back([&, stored, procedural]() -> Geometry {
                if (procedural(GeometryClass::Paths)) return build_procedural_path_joints(scene);
                return stored(build_stored_path_joints(scene));
            });
    }
    if (!scene.trees.empty())
        builders.push_back([&, procedural]() -> Geometry {
            if (procedural(GeometryClass::Trees)) return build_procedural_trees(scene);
            return build_stored_trees(scene);
        });
    // Retaining walls (format 1.2) stand only on a field; none without one.
    if (!scene.retaining_walls.empty() && !scene.terrain.empty())
        builders.push_back([&, stored, procedural]() -> Geometry {
            if (procedural(GeometryClass::RetainingWalls)) return build_procedural_retaining_walls(scene);
            return stored(build_stored_retaining_walls(scene));
        });
    builders.push_back([&, stored, procedural]() -> Geometry {
        if (procedural(GeometryClass::Lamps)) return build_procedural_lamps(scene);
        return stored(build_stored_lamps(scene));
    });
    return builders;
}

}  // namespace

std::unique_ptr<RenderScene> build_render_geometry(const Scene& scene, const GeometryModes& modes,
                                                   const FacadeOptions& facades, const ProgressSettings& progress,
                                                   const std::function<void()>& before_buildings) {
    // Buildings are nearly all of the work (every facade triangle), so they measure it.
    Progress geometry_progress("geometry", scene.buildings.size(), progress);
    // Each builder reads only the scene, so they run side by side and are added in their order
    // whatever finished first. The buildings' (the first) come last when the caller frees what
    // the others read before them.
    const auto builders = class_builders(scene, modes, facades, geometry_progress);
    std::vector<Geometry> geometries(builders.size());
    const size_t first = before_buildings ? 1 : 0;
    tbb::parallel_for(first, builders.size(), [&](size_t i) { geometries[i] = builders[i](); });
    if (before_buildings) {
        before_buildings();
        geometries[0] = builders[0]();
    }
    geometry_progress.finish();
    auto render_scene = std::make_unique<RenderScene>();
    for (Geometry& geometry : geometries) render_scene->add(std::move(geometry));
    return render_scene;
}

std::unique_ptr<RenderScene> build_render_scene(const Scene& scene, const GeometryModes& modes,
                                                const FacadeOptions& facades, const ProgressSettings& progress) {
    auto render_scene = build_render_geometry(scene, modes, facades, progress);
    render_scene->commit(progress);
    return render_scene;
}

namespace {

template <class Objects>
void release(Objects& objects) {
    Objects().swap(objects);
}

void give_back_pages() {
#ifdef __GLIBC__
    malloc_trim(0);  // millions of small blocks: give the pages back, Embree allocates its own
#endif
}

}  // namespace

void release_geometry_only_classes(Scene& scene) {
    release(scene.roads);
    release(scene.joints);
    release(scene.sidewalks);
    release(scene.land_cover);
    release(scene.trees);
    release(scene.paths);
    release(scene.path_joints);
    release(scene.crossings);
    release(scene.retaining_walls);
    release(scene.lamps);
    give_back_pages();
}

void release_buildings(Scene& scene, bool keep_walls) {
    if (keep_walls) {
        for (Building& building : scene.buildings) release(building.roof_faces);
    } else {
        release(scene.buildings);
    }
    give_back_pages();
}

}  // namespace citygen
