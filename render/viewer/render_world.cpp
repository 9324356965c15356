#include "render/viewer/render_world.h"

#include "render/geometry/build_render_scene.h"

namespace citygen {

namespace {

std::string geometry_key(const Job& job, const FacadeOptions& facades) {
    std::string key;
    for (GeometryMode mode : job.modes.mode) key += mode == GeometryMode::Procedural ? 'p' : 's';
    return key + ' ' + std::to_string(facades.shop_probability);
}

std::string lights_key(const LightOptions& lights) {
    return std::to_string(lights.lamps) + ' ' + std::to_string(lights.lamp_lumens) + ' ' +
           std::to_string(lights.lamp_kelvin) + ' ' + std::to_string(lights.lit_windows) + ' ' +
           std::to_string(static_cast<int>(lights.sampler));
}

}  // namespace

RenderWorld::RenderWorld(const Scene& scene, bool quiet)
    : scene_(scene), quiet_(quiet), materials_(default_materials()), looks_(scene) {}

bool RenderWorld::update(const ViewRequest& request) {
    const Options& o = request.options;
    const Job& job = request.job;
    const FacadeOptions facades = facade_options(o, scene_);
    bool rebuilt = false;
    const std::string geometry = geometry_key(job, facades);
    if (!render_scene_ || geometry != geometry_key_) {
        render_scene_.reset();  // the old one's memory goes first
        lights_.reset();        // its windows follow the facades
        render_scene_ = build_render_scene(scene_, job.modes, facades, ProgressSettings{quiet_});
        geometry_key_ = geometry;
        rebuilt = true;
    }
    sky_ = make_sky(o, job);
    const LightOptions lights = lights_under(*sky_, job.lights);
    const std::string light = lights_key(lights);
    if (!lights_ || light != lights_key_) {
        lights_ = std::make_unique<SceneLights>(scene_, facades, lights);
        lights_key_ = light;
    }
    integrator_ = job.settings.integrator;
    set_atmosphere(o, scene_, integrator_);
    return rebuilt;
}

PathContext RenderWorld::context() const {
    return PathContext{*render_scene_, materials_, *sky_, integrator_, &looks_, lights_.get()};
}

size_t RenderWorld::bytes() const {
    if (!render_scene_) return 0;
    return static_cast<size_t>(std::max<int64_t>(0, render_scene_->embree_bytes())) + render_scene_->buffer_bytes() +
           (lights_ ? lights_->bytes() : 0);
}

}  // namespace citygen
