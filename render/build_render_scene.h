// From a loaded scene file to the Embree scene the integrator traces: one geometry per object
// class, built in the mode chosen for that class.
#pragma once

#include <memory>

#include "facade.h"
#include "geometry_mode.h"
#include "render_scene.h"
#include "scene.h"

namespace citygen {

// `facades` sets the facade rules' seed and shop probability; both modes build the same facades.
std::unique_ptr<RenderScene> build_render_scene(const Scene& scene, const GeometryModes& modes,
                                                const FacadeOptions& facades = FacadeOptions{});

}  // namespace citygen
