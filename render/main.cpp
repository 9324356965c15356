// render: a citygen scene in, a path-traced image out. The pipeline, top to bottom:
// load scene -> build Embree scene (per-class geometry mode) -> camera and sky -> render -> write.
// With --serve, the same steps run for each view a web page asks for (render/viewer/).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <functional>
#include <memory>
#include <string>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>

#include "common/error.h"
#include "common/output_target.h"
#include "common/scene_info.h"
#include "common/scene_io.h"
#include "render/camera/camera.h"
#include "render/cli_values.h"
#include "render/huge_pages.h"
#include "render/options.h"
#include "render/export/export_gltf.h"
#include "render/export/export_ply.h"
#include "render/film/exposure.h"
#include "render/film/image_output.h"
#include "render/film/render_image.h"
#include "render/geometry/build_render_scene.h"
#include "render/geometry/ground.h"
#include "render/lights/scene_lights.h"
#include "render/lights/sky.h"
#include "render/materials/bsdf.h"
#include "render/production/memory_estimate.h"
#include "render/production/render_frames.h"
#include "render/production/render_report.h"
#include "render/scene/merge_scenes.h"
#include "render/viewer/serve_viewer.h"

using namespace citygen;

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

void print_lights_info(const SceneLights& lights, LightSamplerKind sampler) {
    std::printf("lights: %zu lamps, %zu window strips (%llu of %llu windows lit), %s sampler, %.1f MB\n"
                "light_lamps: %zu\nlight_window_strips: %zu\nlit_windows: %llu\nwindows: %llu\nlight_bytes: %zu\n",
                lights.lamp_count(), lights.strip_count(), static_cast<unsigned long long>(lights.lit_window_count()),
                static_cast<unsigned long long>(lights.window_count()), to_string(sampler), lights.bytes() / 1e6,
                lights.lamp_count(), lights.strip_count(), static_cast<unsigned long long>(lights.lit_window_count()),
                static_cast<unsigned long long>(lights.window_count()), lights.bytes());
}

void print_memory(const RenderScene& render_scene, const SceneLights& lights) {
    print_memory_info(render_scene, stdout);
    std::printf("light_bytes: %zu\n", lights.bytes());
}

// Seconds of the phases besides the tracing: loading the file, building geometry and BVH,
// metering the exposure (a small render of the frame), writing.
struct PhaseSeconds {
    double load = 0, build = 0, exposure = 0, write = 0, render_cpu = 0;
};

void print_stats(const RenderStats& stats, const PhaseSeconds& phases, const Camera& camera, const Sky& sky,
                 double exposure, const SceneLights& lights, const Options& o) {
    std::printf("load_seconds: %.3f\nbuild_seconds: %.3f\nexposure_seconds: %.3f\nwrite_seconds: %.3f\n", phases.load,
                phases.build, phases.exposure, phases.write);
    std::printf("spp: %d\n", stats.spp);
    if (o.denoise) std::printf("denoise_seconds: %.3f\n", stats.denoise_seconds);
    std::printf("render_cpu_seconds: %.3f\n", phases.render_cpu);
    std::printf("render_seconds: %.3f\nrays: %llu\nrays_per_second: %.0f\n", stats.seconds,
                static_cast<unsigned long long>(stats.rays), stats.rays / std::max(stats.seconds, 1e-9));
    // The view actually used (also the automatic one), so another renderer can match it.
    const Vec3 p = camera.position(), t = camera.position() + camera.forward() * 100;
    std::printf("camera: %.3f,%.3f,%.3f\nlook_at: %.3f,%.3f,%.3f\nfov: %.3f\n", p.x, p.y, p.z, t.x, t.y, t.z, o.fov);
    const Vec3 sun = sky.sun_direction();
    std::printf("sun_direction: %.5f,%.5f,%.5f\nsun_irradiance: %.4f\n", sun.x, sun.y, sun.z,
                sky.has_sun() ? luminance(sky.sun_radiance()) * sky.sun_solid_angle() : 0.0);
    std::printf("sun_elevation: %.3f\nexposure_ev: %.3f\nlights: %zu\n", sky.sun_elevation(),
                ev_from_exposure(exposure), lights.light_count());
}

// An orbit goes round the automatic view's centre: where its line of sight meets the ground.
Animation make_animation(const Options& o, const Job& job, const Camera& camera, const Scene& scene) {
    Animation animation;
    animation.frames = job.frames;
    animation.fps = o.fps;
    animation.output_pattern = o.output;
    if (o.orbit) {
        const Vec3 start = camera.position(), forward = camera.forward();
        // On a field, the ground's height where the sight line meets the flat ground there, refined.
        Vec3 centre = start + forward * 100.0;
        double ground_z = scene.ground.z;
        for (int round = 0; round < 4 && forward.z < -1e-6; ++round) {
            centre = start + forward * ((ground_z - start.z) / forward.z);
            ground_z = ground_height(scene, centre.x, centre.y);
        }
        animation.view = [=, &scene, fov = o.fov, seconds = o.orbit_seconds](double t) {
            CameraKey key = orbit_at(start, centre, fov, seconds, t);
            key.position = above_ground(scene, key.position);  // never inside a hill
            return key;
        };
    } else {
        const CameraPath& path = job.camera_path;
        animation.view = [&path](double t) { return camera_path_at(path, t); };
    }
    return animation;
}

// An explicit camera under the ground sees the inside of a hill (the automatic view and the
// orbit are kept above it): say so on one line and render what was asked.
void note_camera_below_ground(const Scene& scene, Vec3 camera) {
    const double below = ground_height(scene, camera.x, camera.y) - camera.z;
    if (below > 0)
        std::fprintf(stderr, "render: note: the camera is %.1f m below the ground at %.1f,%.1f\n", below, camera.x,
                     camera.y);
}

int run(const Options& o) {
    Job job = prepare_job(o);
    if (!o.serve.empty()) {
        if (o.scene_paths.size() > 1) throw Error("--serve takes one scene, not " + std::to_string(o.scene_paths.size()));
        return serve_viewer(o);
    }
    RenderSettings& settings = job.settings;
    PhaseSeconds phases;
    const Clock::time_point start = Clock::now();
    Scene scene = load_scenes(o.scene_paths);
    phases.load = seconds_since(start);
    if (o.print_scene_info) print_scene_info(scene, o.scene_path, stdout);
    const bool builds = !o.output.empty() || !o.export_ply_path.empty() || !o.export_gltf_path.empty() ||
                        o.print_memory_info || o.print_geometry_info;
    if (!builds) return 0;  // the summary alone needs no geometry
    sink_field_under_sea(scene);  // before anything stands on the field

    // User textures are read before the long geometry build, so a bad --texture-dir fails fast.
    std::unique_ptr<BuildingTextures> textures;
    if (!o.texture_dir.empty()) {
        const double pixel_angle = 2 * std::tan(0.5 * o.fov * kPi / 180) / settings.height;
        textures = std::make_unique<BuildingTextures>(o.texture_dir, pixel_angle);
    }
    const FacadeOptions facades = facade_options(o, scene);
    const Clock::time_point build_start = Clock::now();
    check_memory_fits(estimate_render_memory(scene, job.modes, facades, settings));
    // The lights, the looks and the automatic view read the scene's objects (lamps on decks, a
    // town without buildings), so they come first, while nothing else is held. Then only the
    // glTF export and lit windows need the objects: each class goes once its geometry is built,
    // before the buildings' geometry (the largest) and the BVH build come on top.
    const Sky sky = make_sky(o, job);
    const SceneLights lights(scene, facades, lights_under(sky, job.lights));
    BuildingLooks building_looks(scene);
    building_looks.use_textures(textures.get());
    const Camera camera = view_camera(o, job, scene);
    const bool release = o.export_gltf_path.empty();
    const std::unique_ptr<RenderScene> render_scene =
        build_render_geometry(scene, job.modes, facades, ProgressSettings{settings.quiet},
                              release ? std::function<void()>([&] { release_geometry_only_classes(scene); }) : nullptr);
    if (release) release_buildings(scene, lights.reads_buildings());
    render_scene->commit(ProgressSettings{settings.quiet});
    phases.build = seconds_since(build_start);
    if (o.print_geometry_info) print_geometry_info(*render_scene, stdout);
    if (o.print_geometry_info) print_lights_info(lights, job.lights.sampler);
    const MaterialTable materials = default_materials();
    if (!o.export_ply_path.empty()) export_ply(*render_scene, materials, o.export_ply_path);
    if (!o.export_gltf_path.empty()) export_gltf(scene, *render_scene, materials, o.export_gltf_path);
    if (o.output.empty()) {
        if (o.print_memory_info) print_memory(*render_scene, lights);
        return 0;
    }

    if (job.want_camera) note_camera_below_ground(scene, parse_point(o.camera, "--camera"));
    set_atmosphere(o, scene, settings.integrator);
    const PathContext context{*render_scene, materials, sky, settings.integrator, &building_looks, &lights};
    // Automatic exposure is metered on the whole frame before rendering (exposure.h), so a
    // region or tile gets its frame's exposure, and each frame of an animation its own.
    auto exposure_for = [&](const Camera& view) { return view_exposure(o, context, view, settings); };
    if (job.animate) {
        render_animation(context, make_animation(o, job, camera, scene), settings, o.denoise, exposure_for);
        return 0;
    }
    const Clock::time_point exposure_start = Clock::now();
    const double exposure = exposure_for(camera);
    phases.exposure = seconds_since(exposure_start);
    // CPU time of all threads while tracing: on a shared machine a steadier measure of cost than
    // the wall clock.
    RenderStats stats;
    const std::clock_t cpu_start = std::clock();
    const Film film = render_view(context, camera, settings, o.denoise, exposure, &stats);
    phases.render_cpu = double(std::clock() - cpu_start) / CLOCKS_PER_SEC;
    if (o.time_limit > 0 && !settings.quiet)
        std::fprintf(stderr, "render: time limit %gs: %d passes (%d spp) in %.2fs\n", o.time_limit, stats.spp,
                     stats.spp, stats.seconds);
    const Clock::time_point write_start = Clock::now();
    write_image(film, o.output, exposure);
    phases.write = seconds_since(write_start);
    if (o.print_memory_info) print_memory(*render_scene, lights);
    if (o.stats) print_stats(stats, phases, camera, sky, exposure, lights, o);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"render: path-trace a citygen scene with Embree"};
    app.set_version_flag("--version", std::string("citygen render ") + CITYGEN_VERSION);
    Options o;
    add_file_and_production_options(app, o);
    add_view_options(app, o);
    add_sky_and_light_options(app, o);
    add_integrator_options(app, o);
    add_geometry_mode_options(app, o);

    try {
        app.parse(argc, argv);
        o.spp_given = app.count("--spp") > 0;
        o.scene_path = o.scene_paths.front();
        restart_with_huge_pages_for(o.scene_paths, argv);
    } catch (const CLI::Success& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::string message = e.what();
        for (char& ch : message)
            if (ch == '\n') ch = ' ';
        std::fprintf(stderr, "render: %s (see --help)\n", message.c_str());
        return 2;
    }
    try {
        std::unique_ptr<tbb::global_control> limit;
        if (o.threads > 0)
            limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, o.threads);
        return run(o);
    } catch (const Error& e) {
        std::fprintf(stderr, "render: %s\n", e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "render: unexpected error: %s\n", e.what());
        return 1;
    }
}
