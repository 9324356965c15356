// From a loaded scene file to the Embree scene the integrator traces: one geometry per object
// class, built in the mode chosen for that class.
#pragma once

#include <functional>
#include <memory>

#include "common/progress.h"
#include "common/scene.h"
#include "render/facade/facade.h"
#include "render/scene/geometry_mode.h"
#include "render/scene/render_scene.h"

namespace citygen {

// `facades` sets the facade rules' seed and shop probability; both modes build the same facades.
// `progress` shows the two long phases on stderr: building geometry (per building) and the BVH.
std::unique_ptr<RenderScene> build_render_scene(const Scene& scene, const GeometryModes& modes,
                                                const FacadeOptions& facades = FacadeOptions{},
                                                const ProgressSettings& progress = ProgressSettings{});

// build_render_scene in two steps, for a caller that frees what only the geometry reads before
// the BVH build adds its own memory: the geometry of every class, then RenderScene::commit.
// With `before_buildings`, the other classes' geometry is built first, then before_buildings()
// runs (release_geometry_only_classes: their objects go before the largest geometry is made),
// then the buildings'.
std::unique_ptr<RenderScene> build_render_geometry(const Scene& scene, const GeometryModes& modes,
                                                   const FacadeOptions& facades = FacadeOptions{},
                                                   const ProgressSettings& progress = ProgressSettings{},
                                                   const std::function<void()>& before_buildings = nullptr);

// Frees the classes that nothing but their geometry reads once the lights, the looks and the
// view are made: roads, joints, sidewalks, land cover, trees, paths, crossings, retaining walls
// and lamps. The geometry keeps its own copy of what it needs; the buildings, the ground, the
// field and the header stay.
void release_geometry_only_classes(Scene& scene);
// Frees the buildings once their geometry is built, or with `keep_walls` (lit windows are
// re-derived from their walls at night) only their roof faces.
void release_buildings(Scene& scene, bool keep_walls);

}  // namespace citygen
