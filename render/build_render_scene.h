// From a loaded scene file to the Embree scene the integrator traces: one geometry per object
// class, built in the mode chosen for that class.
#pragma once

#include <memory>

#include "geometry_mode.h"
#include "render_scene.h"
#include "scene.h"

namespace citygen {

// Throws citygen::Error when a requested mode is not available.
std::unique_ptr<RenderScene> build_render_scene(const Scene& scene, const GeometryModes& modes);

}  // namespace citygen
