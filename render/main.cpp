// render: a citygen scene in, a path-traced image out. The pipeline, top to bottom:
// load scene -> build Embree scene (per-class geometry mode) -> camera and sky -> render -> write.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <memory>
#include <sstream>
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

using namespace citygen;

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

struct Options {
    std::string scene_path, output, export_ply_path, export_gltf_path;
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
};

// A number within [lo, hi]; rejects nan and inf (CLI::Range lets nan through).
CLI::Validator finite_within(double lo, double hi) {
    std::ostringstream range;
    range << "[" << lo << " - " << hi << "]";
    return CLI::Validator(
        [lo, hi, range = range.str()](std::string& text) -> std::string {
            char* end = nullptr;
            const double v = std::strtod(text.c_str(), &end);
            if (end == text.c_str() || *end != '\0' || !(v >= lo && v <= hi))
                return "expected a number in " + range + ", got '" + text + "'";
            return "";
        },
        range.str());
}

std::string format_number(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}

bool parse_aovs(const std::string& text) {
    if (text.empty()) return false;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');)
        if (item != "depth" && item != "normal" && item != "albedo" && item != "id")
            throw Error("--aovs: unknown AOV '" + item + "' (known: depth, normal, albedo, id)");
    return true;
}

// Fails before the (possibly long) render when the image could not be written anyway.
void check_output_path(const std::string& path, const std::string& scene_path) {
    image_format_for(path);
    check_output_target(path, {scene_path});
}

// An export file must have its extension and be a safe target, checked before the work.
void check_export_path(const std::string& path, const std::string& extension, const std::vector<std::string>& inputs) {
    if (path.size() <= extension.size() || path.compare(path.size() - extension.size(), extension.size(), extension) != 0)
        throw Error(path + ": expected a " + extension + " file name");
    check_output_target(path, inputs);
}

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

// The frames of an animation: all of the orbit or camera path, or those --frames names.
FrameRange animation_frames(const Options& o, const CameraPath& camera_path) {
    // An orbit's last frame is the one before it comes round to the first again.
    const FrameRange available =
        o.orbit ? FrameRange{0, static_cast<int>(std::ceil(o.orbit_seconds * o.fps - 1e-9)) - 1}
                : frames_within(camera_path.keys.front().time, camera_path.keys.back().time, o.fps);
    const FrameRange frames = o.frames.empty() ? available : parse_frame_range(o.frames);
    if (frames.first < available.first || frames.last > available.last)
        throw Error("--frames " + o.frames + ": the " + (o.orbit ? "orbit" : "camera path") + " has frames " +
                    std::to_string(available.first) + "-" + std::to_string(available.last) + " at " +
                    format_number(o.fps) + " fps");
    return frames;
}

// The output files: each a safe target of a known format, checked before the work.
void check_outputs(const Options& o, const Job& job) {
    if (job.animate) check_output_path(frame_file_name(o.output, job.frames.first), o.scene_path);
    else if (!o.output.empty()) check_output_path(o.output, o.scene_path);
    if (!o.export_ply_path.empty()) check_output_target(o.export_ply_path, {o.scene_path, o.output});
    if (job.settings.aovs && !o.output.empty() && image_format_for(o.output) != ImageFormat::Exr)
        throw Error("--aovs needs an .exr output");
    if (!o.export_gltf_path.empty())
        check_export_path(o.export_gltf_path, ".glb", {o.scene_path, o.output, o.export_ply_path});
    if (o.output.empty() && o.export_ply_path.empty() && o.export_gltf_path.empty() && !o.print_scene_info &&
        !o.print_memory_info && !o.print_geometry_info)
        throw Error("need -o OUTPUT.png|jpg|exr (see --help)");
}

Job prepare_job(const Options& o) {
    Job job;
    job.modes = GeometryModes::all(o.procedural ? GeometryMode::Procedural : GeometryMode::Stored);
    for (int c = 0; c < kGeometryClassCount; ++c)
        if (!o.geometry[c].empty())
            job.modes.mode[c] = parse_geometry_mode(
                o.geometry[c], std::string("--geometry-") + to_string(static_cast<GeometryClass>(c)));
    job.time = parse_time_of_day(o.time);
    job.lights = o.lights;
    job.lights.sampler = parse_light_sampler(o.light_sampler);
    RenderSettings& settings = job.settings;
    settings = o.render;
    settings.aovs = parse_aovs(o.aovs);
    if (!o.region.empty()) {
        settings.region = parse_region(o.region);
        render_region(settings);  // inside the frame, or fail now
    }
    settings.time_limit_seconds = o.time_limit;
    if (o.time_limit > 0 && !o.spp_given) settings.spp = 1 << 20;  // the time decides
    job.animate = !o.camera_path.empty() || o.orbit;
    if (!o.camera_path.empty() && o.orbit) throw Error("--camera-path and --orbit exclude each other");
    if (job.animate && (!o.camera.empty() || !o.look_at.empty()))
        throw Error("--camera/--look-at and an animation (--camera-path, --orbit) exclude each other");
    if (!job.animate && !o.frames.empty()) throw Error("--frames needs --camera-path or --orbit");
    if (job.animate && o.output.empty()) throw Error("an animation needs -o PATTERN, e.g. -o out_%04d.png");
    if (!o.camera_path.empty()) job.camera_path = read_camera_path(o.camera_path);
    if (job.animate) job.frames = animation_frames(o, job.camera_path);
    job.want_camera = !o.camera.empty() || !o.look_at.empty();
    if (job.want_camera && (o.camera.empty() || o.look_at.empty()))
        throw Error("--camera and --look-at go together");
    if (job.want_camera) check_view(parse_point(o.camera, "--camera"), parse_point(o.look_at, "--look-at"));
    check_outputs(o, job);
    return job;
}

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

// Seconds of the phases besides the tracing: loading the file, building geometry and BVH, writing.
struct PhaseSeconds {
    double load = 0, build = 0, write = 0, render_cpu = 0;
};

void print_stats(const RenderStats& stats, const PhaseSeconds& phases, const Camera& camera, const Sky& sky,
                 double exposure, const SceneLights& lights, const Options& o) {
    std::printf("load_seconds: %.3f\nbuild_seconds: %.3f\nwrite_seconds: %.3f\n", phases.load, phases.build,
                phases.write);
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
    RenderSettings& settings = job.settings;
    PhaseSeconds phases;
    const Clock::time_point start = Clock::now();
    Scene scene = load_scene(o.scene_path);
    phases.load = seconds_since(start);
    if (o.print_scene_info) print_scene_info(scene, o.scene_path, stdout);
    sink_field_under_sea(scene);  // before anything stands on the field

    // User textures are read before the long geometry build, so a bad --texture-dir fails fast.
    std::unique_ptr<BuildingTextures> textures;
    if (!o.texture_dir.empty()) {
        const double pixel_angle = 2 * std::tan(0.5 * o.fov * kPi / 180) / settings.height;
        textures = std::make_unique<BuildingTextures>(o.texture_dir, pixel_angle);
    }
    // Facades follow the scene's seed (not --seed, which drives the pixel streams), so every
    // render of a scene shows the same buildings.
    FacadeOptions facades;
    facades.seed = scene.header.seed;
    facades.shop_probability = o.shop_probability;
    const Clock::time_point build_start = Clock::now();
    check_memory_fits(estimate_render_memory(scene, job.modes, facades, settings));
    const std::unique_ptr<RenderScene> render_scene =
        build_render_scene(scene, job.modes, facades, ProgressSettings{settings.quiet});
    phases.build = seconds_since(build_start);
    if (o.print_geometry_info) print_geometry_info(*render_scene, stdout);
    // Lamps and lit windows glow once the sun is down (dusk, night, or --sun-elevation below 1).
    const Sky sky = Sky::for_settings(SkySettings{job.time, o.sun_elevation, o.sun_azimuth, o.moon});
    if (!(sky.sun_elevation() < kLightsOnBelowElevation)) job.lights.lamps = false, job.lights.lit_windows = 0;
    const SceneLights lights(scene, facades, job.lights);
    if (o.print_geometry_info) print_lights_info(lights, job.lights.sampler);
    const MaterialTable materials = default_materials();
    if (!o.export_ply_path.empty()) export_ply(*render_scene, materials, o.export_ply_path);
    if (!o.export_gltf_path.empty()) export_gltf(scene, *render_scene, materials, o.export_gltf_path);
    if (o.output.empty()) {
        if (o.print_memory_info) print_memory(*render_scene, lights);
        return 0;
    }

    const Camera camera =
        job.want_camera ? Camera::look_at(parse_point(o.camera, "--camera"), parse_point(o.look_at, "--look-at"),
                                          o.fov, settings.width, settings.height)
                        : framing_camera(scene, o.fov, settings.width, settings.height);
    if (job.want_camera) note_camera_below_ground(scene, parse_point(o.camera, "--camera"));
    settings.integrator.fog.density = o.fog;
    settings.integrator.fog.top_z = scene.ground.z + o.fog_height;
    settings.integrator.haze_extinction = o.visibility_km > 0 ? 3.912 / (o.visibility_km * 1000) : 0;
    BuildingLooks building_looks(scene);
    building_looks.use_textures(textures.get());
    const PathContext context{*render_scene, materials, sky, settings.integrator, &building_looks, &lights};
    // Automatic exposure is metered on the whole frame before rendering (exposure.h), so a
    // region or tile gets its frame's exposure, and each frame of an animation its own.
    auto exposure_for = [&](const Camera& view) {
        return std::isnan(o.exposure_ev) ? metered_exposure(context, view, settings) : exposure_from_ev(o.exposure_ev);
    };
    if (job.animate) {
        render_animation(context, make_animation(o, job, camera, scene), settings, o.denoise, exposure_for);
        return 0;
    }
    const double exposure = exposure_for(camera);
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

// The scene, the image and the view.
void add_image_options(CLI::App& app, Options& o) {
    RenderSettings& r = o.render;
    app.add_option("scene", o.scene_path, "scene file written by osmparse")->required();
    app.add_option("-o,--output", o.output, "image to write: .png, .jpg (tone-mapped sRGB) or .exr (linear)");
    app.add_option("--width", r.width, "image width in pixels")->check(CLI::Range(1, 16384))->capture_default_str();
    app.add_option("--height", r.height, "image height in pixels")->check(CLI::Range(1, 16384))->capture_default_str();
    app.add_option("--spp", r.spp, "samples per pixel")->check(CLI::Range(1, 1 << 20))->capture_default_str();
    app.add_option("--seed", r.seed, "seed of the per-pixel random streams")->capture_default_str();
    app.add_option("--threads", o.threads, "worker threads (0: all cores)")->check(CLI::Range(0, 4096))
        ->capture_default_str();
    app.add_option("--camera", o.camera, "camera position X,Y,Z in scene metres (with --look-at)");
    app.add_option("--look-at", o.look_at, "point the camera looks at, X,Y,Z in scene metres");
    app.add_option("--fov", o.fov, "vertical field of view in degrees")->check(CLI::Range(1.0, 170.0))
        ->capture_default_str();
}

// Time of day, sun, exposure, lamps, windows and atmosphere.
void add_sky_and_light_options(CLI::App& app, Options& o) {
    app.add_option("--time", o.time, "day, sunset, dusk or night")->capture_default_str();
    app.add_option("--sun-elevation", o.sun_elevation,
                   "sun elevation in degrees (below 1: twilight or night, lamps and windows on); default from --time")
        ->check(finite_within(-90, 90));
    app.add_option("--sun-azimuth", o.sun_azimuth, "sun azimuth in degrees clockwise from north; default from --time")
        ->check(finite_within(-360, 360));
    app.add_flag("--moon", o.moon, "a full moon lights the night (when the sun is below the horizon)");
    app.add_option("--exposure", o.exposure_ev,
                   "exposure value at ISO 100 (e.g. 15 sunny day, 9 dusk, 3 street lamps); default automatic")
        ->check(finite_within(-20, 30));
    app.add_option("--lamp-power", o.lights.lamp_lumens, "luminous flux of each street lamp in lumens")
        ->check(finite_within(0, 1e7))->capture_default_str();
    app.add_option("--lamp-kelvin", o.lights.lamp_kelvin,
                   "colour temperature of the lamps (2000 sodium orange .. 6500 cold LED)")
        ->check(finite_within(1667, 25000))->capture_default_str();
    app.add_option("--lit-windows", o.lights.lit_windows, "share of windows lit at night (shop fronts more often)")
        ->check(finite_within(0, 1))->capture_default_str();
    app.add_option("--fog", o.fog,
                   "ground fog: scattering coefficient per metre (0.01 thin, 0.05 thick; 0 none); lamp haloes at night")
        ->check(finite_within(0, 10))->capture_default_str();
    app.add_option("--fog-height", o.fog_height, "the fog fills the air up to this many metres above the ground")
        ->check(finite_within(0, 10000))->capture_default_str();
    app.add_option("--visibility", o.visibility_km,
                   "clear-air visibility in km for the aerial perspective on camera rays (0: none)")
        ->check(finite_within(0, 1000))->capture_default_str();
    app.add_option("--light-sampler", o.light_sampler,
                   "how next-event estimation picks a lamp or window: tree (light BVH), power or uniform")
        ->capture_default_str();
}

// Path length and Russian roulette.
void add_integrator_options(CLI::App& app, Options& o) {
    RenderSettings& r = o.render;
    app.add_option("--max-depth", r.integrator.max_depth, "bounces after the first hit")
        ->check(CLI::Range(0, 1000))->capture_default_str();
    app.add_option("--rr-depth", r.integrator.rr_depth, "bounces always traced before Russian roulette starts")
        ->check(CLI::Range(0, 1000))->capture_default_str();
    app.add_option("--rr-prob", r.integrator.rr_prob,
                   "least survival probability of a roulette step: a path survives with its largest "
                   "throughput component, clamped to [rr-prob, 1], and is reweighted by 1/survival")
        ->check(CLI::Range(0.01, 1.0))->capture_default_str();
}

// Geometry mode per class, the buildings' looks and AOVs.
void add_geometry_options(CLI::App& app, Options& o) {
    app.add_flag("--procedural", o.procedural, "every class in procedural geometry mode");
    for (int c = 0; c < kGeometryClassCount; ++c) {
        const std::string name = to_string(static_cast<GeometryClass>(c));
        app.add_option("--geometry-" + name, o.geometry[c], "stored or procedural geometry for " + name);
    }
    app.add_option("--shop-probability", o.shop_probability,
                   "chance that a building has a ground floor of shop windows")
        ->check(CLI::Range(0.0, 1.0))
        ->capture_default_str();
    app.add_option("--aovs", o.aovs, "extra EXR channels: any of depth,normal,albedo,id");
    app.add_option("--texture-dir", o.texture_dir,
                   "tile textures replacing the wall/roof patterns: DIR/<material>.png (brick, plaster, ...) "
                   "and DIR/roof_<material>.png (roof_tiles, slate, ...), one repeat per 2 m");
}

// Exports and what is printed.
void add_output_options(CLI::App& app, Options& o) {
    RenderSettings& r = o.render;
    app.add_option("--export-ply", o.export_ply_path, "write the stored triangles as binary PLY (material per face)");
    app.add_option("--export-gltf", o.export_gltf_path,
                   "write the stored geometry as binary glTF (.glb): a node per building with its OSM id, PBR "
                   "materials, y-up");
    app.add_flag("--print-scene-info", o.print_scene_info, "the summary osmparse --info prints: counts, bounds, origin, options");
    app.add_flag("--print-memory-info", o.print_memory_info, "Embree and buffer bytes, peak RSS");
    app.add_flag("--print-scene-geometry-info", o.print_geometry_info, "triangles or primitives per class");
    app.add_flag("--stats", o.stats, "print render_seconds:, rays_per_second: and the camera used");
    app.add_flag("-q,--quiet", r.quiet, "no progress bar");
}

// Tiles, animations, time budgets and denoising.
void add_production_options(CLI::App& app, Options& o) {
    app.add_option("--region", o.region,
                   "render only pixels X0,Y0,X1,Y1 (x in [X0,X1), y in [Y0,Y1)) of the full frame; they equal the "
                   "same pixels of the full render");
    app.add_option("--camera-path", o.camera_path,
                   "animate along keyframes (CSV: time,x,y,z,look_x,look_y,look_z,fov per line); -o is a pattern "
                   "like out_%04d.png");
    app.add_flag("--orbit", o.orbit, "animate one turn around the automatic view's centre (see --orbit-seconds)");
    app.add_option("--orbit-seconds", o.orbit_seconds, "duration of the --orbit turn")
        ->check(finite_within(0.01, kMaxPathSeconds))->capture_default_str();
    app.add_option("--frames", o.frames, "frames A-B (or N) of the animation; default: all");
    app.add_option("--fps", o.fps, "frames per second of the animation (frame n shows time n / fps)")
        ->check(finite_within(0.01, 1000.0))->capture_default_str();
    app.add_option("--time-limit", o.time_limit,
                   "render whole passes (1 spp each) while the next fits in SECONDS; --spp, if given, caps them")
        ->check(finite_within(0.0, 1e9));
    app.add_flag("--denoise", o.denoise,
                 "edge-avoiding a-trous filter guided by normal, depth, albedo and id (EXR keeps raw.R/G/B)");
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"render: path-trace a citygen scene with Embree"};
    app.set_version_flag("--version", std::string("citygen render ") + CITYGEN_VERSION);
    Options o;
    add_image_options(app, o);
    add_sky_and_light_options(app, o);
    add_integrator_options(app, o);
    add_geometry_options(app, o);
    add_output_options(app, o);
    add_production_options(app, o);

    try {
        app.parse(argc, argv);
        o.spp_given = app.count("--spp") > 0;
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
