#include "render/options.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include <CLI/CLI.hpp>

#include "common/error.h"
#include "common/output_target.h"
#include "render/cli_values.h"
#include "render/film/exposure.h"
#include "render/film/image_output.h"
#include "render/production/render_frames.h"

namespace citygen {

std::string format_number(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%g", value);
    return text;
}


namespace {

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

bool parse_aovs(const std::string& text) {
    if (text.empty()) return false;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');)
        if (item != "depth" && item != "normal" && item != "albedo" && item != "id")
            throw Error("--aovs: unknown AOV '" + item + "' (known: depth, normal, albedo, id)");
    return true;
}

// Fails before the (possibly long) render when the image could not be written anyway.
void check_output_path(const std::string& path, const std::vector<std::string>& scene_paths) {
    image_format_for(path);
    check_output_target(path, scene_paths);
}

// Every file read, so no output overwrites one.
std::vector<std::string> with_inputs(const Options& o, std::vector<std::string> others) {
    std::vector<std::string> all = o.scene_paths.empty() ? std::vector<std::string>{o.scene_path} : o.scene_paths;
    all.insert(all.end(), others.begin(), others.end());
    return all;
}

// An export file must have its extension and be a safe target, checked before the work.
void check_export_path(const std::string& path, const std::string& extension, const std::vector<std::string>& inputs) {
    if (path.size() <= extension.size() || path.compare(path.size() - extension.size(), extension.size(), extension) != 0)
        throw Error(path + ": expected a " + extension + " file name");
    check_output_target(path, inputs);
}

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
    if (job.animate) check_output_path(frame_file_name(o.output, job.frames.first), with_inputs(o, {}));
    else if (!o.output.empty()) check_output_path(o.output, with_inputs(o, {}));
    if (!o.export_ply_path.empty()) check_output_target(o.export_ply_path, with_inputs(o, {o.output}));
    if (job.settings.aovs && !o.output.empty() && image_format_for(o.output) != ImageFormat::Exr)
        throw Error("--aovs needs an .exr output");
    if (!o.export_gltf_path.empty())
        check_export_path(o.export_gltf_path, ".glb", with_inputs(o, {o.output, o.export_ply_path}));
    if (o.output.empty() && o.export_ply_path.empty() && o.export_gltf_path.empty() && !o.print_scene_info &&
        !o.print_memory_info && !o.print_geometry_info)
        throw Error("need -o OUTPUT.png|jpg|exr (see --help)");
}

}  // namespace

// A view's part of the job: modes, time, lights and settings, and the camera if given.
Job prepare_view_job(const Options& o) {
    Job job;
    job.modes = GeometryModes::all(o.procedural ? GeometryMode::Procedural : GeometryMode::Stored);
    for (int c = 0; c < kGeometryClassCount; ++c)
        if (!o.geometry[c].empty())
            job.modes.mode[c] = parse_geometry_mode(
                o.geometry[c], std::string("--geometry-") + to_string(static_cast<GeometryClass>(c)));
    job.time = parse_time_of_day(o.time);
    job.lights = o.lights;
    job.lights.sampler = parse_light_sampler(o.light_sampler);
    job.settings = o.render;
    job.want_camera = !o.camera.empty() || !o.look_at.empty();
    if (job.want_camera && (o.camera.empty() || o.look_at.empty()))
        throw Error("--camera and --look-at go together");
    if (job.want_camera) check_view(parse_point(o.camera, "--camera"), parse_point(o.look_at, "--look-at"));
    return job;
}

Job prepare_job(const Options& o) {
    Job job = prepare_view_job(o);
    RenderSettings& settings = job.settings;
    settings.aovs = parse_aovs(o.aovs);
    if (!o.region.empty()) {
        settings.region = parse_region(o.region);
        render_region(settings);  // inside the frame, or fail now
    }
    settings.time_limit_seconds = o.time_limit;
    if (o.time_limit > 0 && !o.spp_given) settings.spp = 1 << 20;  // the time decides
    job.animate = !o.camera_path.empty() || o.orbit;
    if (!o.camera_path.empty() && o.orbit) throw Error("--camera-path and --orbit exclude each other");
    if (job.animate && job.want_camera)
        throw Error("--camera/--look-at and an animation (--camera-path, --orbit) exclude each other");
    if (!job.animate && !o.frames.empty()) throw Error("--frames needs --camera-path or --orbit");
    if (job.animate && o.output.empty()) throw Error("an animation needs -o PATTERN, e.g. -o out_%04d.png");
    if (!o.serve.empty() && (job.animate || !o.output.empty()))
        throw Error("--serve renders in the browser: it takes no -o, --camera-path or --orbit");
    if (!o.camera_path.empty()) job.camera_path = read_camera_path(o.camera_path);
    if (job.animate) job.frames = animation_frames(o, job.camera_path);
    if (o.serve.empty()) check_outputs(o, job);
    return job;
}

FacadeOptions facade_options(const Options& o, const Scene& scene) {
    FacadeOptions facades;
    facades.seed = scene.header.seed;
    facades.shop_probability = o.shop_probability;
    return facades;
}

Sky make_sky(const Options& o, const Job& job) {
    return Sky::for_settings(SkySettings{job.time, o.sun_elevation, o.sun_azimuth, o.moon});
}

LightOptions lights_under(const Sky& sky, LightOptions lights) {
    if (!(sky.sun_elevation() < kLightsOnBelowElevation)) lights.lamps = false, lights.lit_windows = 0;
    return lights;
}

void set_atmosphere(const Options& o, const Scene& scene, IntegratorSettings& integrator) {
    integrator.fog.density = o.fog;
    integrator.fog.top_z = scene.ground.z + o.fog_height;
    integrator.haze_extinction = o.visibility_km > 0 ? 3.912 / (o.visibility_km * 1000) : 0;
}

Camera view_camera(const Options& o, const Job& job, const Scene& scene) {
    const RenderSettings& s = job.settings;
    return job.want_camera ? Camera::look_at(parse_point(o.camera, "--camera"), parse_point(o.look_at, "--look-at"),
                                             o.fov, s.width, s.height)
                           : framing_camera(scene, o.fov, s.width, s.height);
}

double view_exposure(const Options& o, const PathContext& context, const Camera& camera,
                     const RenderSettings& settings) {
    return std::isnan(o.exposure_ev) ? metered_exposure(context, camera, settings) : exposure_from_ev(o.exposure_ev);
}

void add_view_options(CLI::App& app, Options& o) {
    RenderSettings& r = o.render;
    app.add_option("--width", r.width, "image width in pixels")->check(CLI::Range(1, 16384))->capture_default_str();
    app.add_option("--height", r.height, "image height in pixels")->check(CLI::Range(1, 16384))->capture_default_str();
    app.add_option("--spp", r.spp, "samples per pixel")->check(CLI::Range(1, 1 << 20))->capture_default_str();
    app.add_option("--seed", r.seed, "seed of the per-pixel random streams")->capture_default_str();
    app.add_option("--camera", o.camera, "camera position X,Y,Z in scene metres (with --look-at)");
    app.add_option("--look-at", o.look_at, "point the camera looks at, X,Y,Z in scene metres");
    app.add_option("--fov", o.fov, "vertical field of view in degrees")->check(CLI::Range(1.0, 170.0))
        ->capture_default_str();
    app.add_flag("--denoise", o.denoise,
                 "first-order regression filter guided by normal, depth, albedo and direct light (EXR keeps raw.R/G/B)");
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
    app.add_flag("--no-gather-panes{false}", r.gather_panes,
                 "let camera rays alone find lit panes a few pixels wide (the same expected image, noisier "
                 "from afar; for checking the film's gathering)");
}

void add_geometry_mode_options(CLI::App& app, Options& o) {
    app.add_flag("--procedural", o.procedural, "every class in procedural geometry mode");
    for (int c = 0; c < kGeometryClassCount; ++c) {
        const std::string name = to_string(static_cast<GeometryClass>(c));
        app.add_option("--geometry-" + name, o.geometry[c], "stored or procedural geometry for " + name);
    }
    app.add_option("--shop-probability", o.shop_probability,
                   "chance that a building has a ground floor of shop windows")
        ->check(CLI::Range(0.0, 1.0))
        ->capture_default_str();
}

void add_file_and_production_options(CLI::App& app, Options& o) {
    RenderSettings& r = o.render;
    app.add_option("scene", o.scene_paths,
                   "scene file written by osmparse; several: the tiles of one region (parse_farm.sh), rendered as one")
        ->required();
    app.add_option("-o,--output", o.output, "image to write: .png, .jpg (tone-mapped sRGB) or .exr (linear)");
    app.add_option("--threads", o.threads, "worker threads (0: all cores)")->check(CLI::Range(0, 4096))
        ->capture_default_str();
    app.add_option("--aovs", o.aovs, "extra EXR channels: any of depth,normal,albedo,id");
    app.add_option("--texture-dir", o.texture_dir,
                   "tile textures replacing the wall/roof patterns: DIR/<material>.png (brick, plaster, ...) "
                   "and DIR/roof_<material>.png (roof_tiles, slate, ...), one repeat per 2 m");
    // Exports and what is printed.
    app.add_option("--export-ply", o.export_ply_path, "write the stored triangles as binary PLY (material per face)");
    app.add_option("--export-gltf", o.export_gltf_path,
                   "write the stored geometry as binary glTF (.glb): a node per building with its OSM id, PBR "
                   "materials, y-up");
    app.add_flag("--print-scene-info", o.print_scene_info, "the summary osmparse --info prints: counts, bounds, origin, options");
    app.add_flag("--print-memory-info", o.print_memory_info, "Embree and buffer bytes, peak RSS");
    app.add_flag("--print-scene-geometry-info", o.print_geometry_info, "triangles or primitives per class");
    app.add_flag("--stats", o.stats, "print render_seconds:, rays_per_second: and the camera used");
    app.add_flag("-q,--quiet", r.quiet, "no progress bar");
    // Tiles, animations and time budgets.
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
    app.add_option("--serve", o.serve,
                   "[HOST:]PORT: serve the interactive viewer (a web page) instead of writing an image; "
                   "HOST defaults to 127.0.0.1, any other host needs the token printed with the URL");
    app.add_option("--serve-out", o.serve_out, "folder where the viewer's \"Save image\" writes (default: .)");
}

}  // namespace citygen
