// render's command line: the options, what they ask for, and the steps from options to a view
// that the CLI and the viewer (render --serve) share, so every state of the viewer is a command
// line and a still saved from it has the bytes the command writes.
#pragma once

#include <cmath>
#include <string>
#include <vector>

#include "render/camera/camera.h"
#include "render/camera/camera_path.h"
#include "render/facade/facade.h"
#include "render/film/render_image.h"
#include "render/lights/scene_lights.h"
#include "render/lights/sky.h"
#include "render/scene/geometry_mode.h"

namespace CLI {
class App;
}

namespace citygen {

struct Options {
    std::string scene_path, output, export_ply_path, export_gltf_path;  // scene_path: the first scene
    std::vector<std::string> scene_paths;  // every scene given: tiles merged into one (merge_scenes.h)
    RenderSettings render;
    int threads = 0;
    std::string camera, look_at;
    double fov = 50;
    std::string time = "day";
    bool procedural = false;
    std::string geometry[kGeometryClassCount];
    double shop_probability = FacadeOptions{}.shop_probability;
    std::string aovs;
    std::string texture_dir;
    bool print_scene_info = false, print_memory_info = false, print_geometry_info = false, stats = false;
    // Production: tiles, animation, time budgets, denoising (see render_frames.h).
    std::string region, camera_path, frames;
    bool orbit = false, denoise = false, spp_given = false;
    double orbit_seconds = 12, fps = 24, time_limit = 0;
    // The night city (lights/, sky, exposure): NaN means automatic / the time's default.
    LightOptions lights;
    std::string light_sampler = "tree";
    double sun_elevation = std::nan(""), sun_azimuth = std::nan("");
    bool moon = false;
    double exposure_ev = std::nan("");
    double fog = 0, fog_height = 60, visibility_km = 20;
    // render --serve [HOST:]PORT: the viewer (render/viewer/).
    std::string serve, serve_out = ".";
};

// The option groups. A view: --width, --height, --spp, --seed, --camera, --look-at, --fov,
// --denoise; sky and lights; integrator; geometry modes. The viewer accepts only these four.
void add_view_options(CLI::App& app, Options& o);
void add_sky_and_light_options(CLI::App& app, Options& o);
void add_integrator_options(CLI::App& app, Options& o);
void add_geometry_mode_options(CLI::App& app, Options& o);
// The CLI's own: the scene and output files, threads, exports, prints, tiles and animations.
void add_file_and_production_options(CLI::App& app, Options& o);

// What the options ask for, checked before the (possibly long) load and build.
struct Job {
    GeometryModes modes;
    TimeOfDay time;
    LightOptions lights;
    RenderSettings settings;
    bool animate = false, want_camera = false;
    CameraPath camera_path;
    FrameRange frames;
};

// The view's part of the job (modes, time, lights, settings, camera); throws citygen::Error.
Job prepare_view_job(const Options& o);
// All of it, for the CLI: also regions, time limits, animations and the output files.
Job prepare_job(const Options& o);

// The steps from options to a rendered view, in the CLI's order.
// Facades follow the scene's seed (not --seed, which drives the pixel streams), so every render
// of a scene shows the same buildings.
FacadeOptions facade_options(const Options& o, const Scene& scene);
Sky make_sky(const Options& o, const Job& job);
// Lamps and lit windows glow once the sun is down (dusk, night, or --sun-elevation below 1).
LightOptions lights_under(const Sky& sky, LightOptions lights);
// Fog up to --fog-height above the ground, aerial haze from --visibility.
void set_atmosphere(const Options& o, const Scene& scene, IntegratorSettings& integrator);
// --camera/--look-at, or the automatic view.
Camera view_camera(const Options& o, const Job& job, const Scene& scene);
// --exposure, or metered on the view (exposure.h).
double view_exposure(const Options& o, const PathContext& context, const Camera& camera,
                     const RenderSettings& settings);

// "%g" of a number, as options print it.
std::string format_number(double value);

}  // namespace citygen
