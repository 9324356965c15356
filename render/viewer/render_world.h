// What the viewer keeps built between frames: the Embree scene (rebuilt when the geometry modes
// or the shop windows change), the lights (when the lamps, windows, sampler or the sun's side of
// the horizon change), the sky, the materials and the buildings' looks. The same steps, in the
// same order, as render's CLI (render/options.h), so a frame equals the CLI's image.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "common/scene.h"
#include "render/facade/building_looks.h"
#include "render/integrator/integrator.h"
#include "render/lights/scene_lights.h"
#include "render/lights/sky.h"
#include "render/materials/materials.h"
#include "render/scene/render_scene.h"
#include "render/viewer/view_request.h"

namespace citygen {

class RenderWorld {
public:
    // `scene` (already sunk under the sea, as the CLI does) must outlive the world.
    RenderWorld(const Scene& scene, bool quiet);

    // Brings everything up to the request's options; returns whether the Embree scene was rebuilt.
    bool update(const ViewRequest& request);

    // The integrator's context for the request last given to update(), with its atmosphere.
    PathContext context() const;
    const RenderScene& render_scene() const { return *render_scene_; }
    const Scene& scene() const { return scene_; }
    size_t bytes() const;  // Embree scene and lights, roughly

private:
    const Scene& scene_;
    bool quiet_;
    MaterialTable materials_;
    BuildingLooks looks_;
    std::string geometry_key_, lights_key_;
    std::unique_ptr<RenderScene> render_scene_;
    std::unique_ptr<SceneLights> lights_;
    std::optional<Sky> sky_;
    IntegratorSettings integrator_;
};

}  // namespace citygen
