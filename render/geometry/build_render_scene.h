// From a loaded scene file to the Embree scene the integrator traces: one geometry per object
// class, built in the mode chosen for that class.
#pragma once

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

}  // namespace citygen
