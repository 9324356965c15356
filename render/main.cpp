// render: a citygen scene in, a path-traced image out. The pipeline, top to bottom:
// load scene -> build Embree scene (per-class geometry mode) -> camera and sky -> render -> write.
#include <chrono>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <tbb/global_control.h>

#include "bsdf.h"
#include "build_render_scene.h"
#include "camera.h"
#include "error.h"
#include "exposure.h"
#include "export_ply.h"
#include "image_output.h"
#include "render_image.h"
#include "render_report.h"
#include "scene_io.h"
#include "scene_lights.h"
#include "sky.h"

using namespace citygen;

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

struct Options {
    std::string scene_path, output, export_ply_path;
    RenderSettings render;
    int threads = 0;
    std::string camera, look_at;
    double fov = 50;
    std::string time = "day";
    bool procedural = false;
    std::string geometry[kGeometryClassCount];
    double shop_probability = FacadeOptions{}.shop_probability;
    std::string aovs;
    bool print_scene_info = false, print_memory_info = false, print_geometry_info = false, stats = false;
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

Vec3 parse_point(const std::string& text, const std::string& option) {
    std::stringstream in(text);
    double v[3];
    char comma1 = 0, comma2 = 0;
    in >> v[0] >> comma1 >> v[1] >> comma2 >> v[2];
    if (in.fail() || comma1 != ',' || comma2 != ',' || !(in >> std::ws).eof() || !std::isfinite(v[0]) ||
        !std::isfinite(v[1]) || !std::isfinite(v[2]))
        throw Error(option + ": expected X,Y,Z in metres, got '" + text + "'");
    return {v[0], v[1], v[2]};
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
void check_output_path(const std::string& path) {
    image_format_for(path);
    const size_t slash = path.find_last_of('/');
    const std::string dir = slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
    if (::access(dir.c_str(), W_OK) != 0) throw Error(path + ": cannot write (directory missing or not writable)");
}

int run(const Options& o) {
    GeometryModes modes = GeometryModes::all(o.procedural ? GeometryMode::Procedural : GeometryMode::Stored);
    for (int c = 0; c < kGeometryClassCount; ++c)
        if (!o.geometry[c].empty())
            modes.mode[c] = parse_geometry_mode(
                o.geometry[c], std::string("--geometry-") + to_string(static_cast<GeometryClass>(c)));
    const TimeOfDay time = parse_time_of_day(o.time);
    LightOptions light_options = o.lights;
    light_options.sampler = parse_light_sampler(o.light_sampler);
    RenderSettings settings = o.render;
    settings.aovs = parse_aovs(o.aovs);
    if (!o.output.empty()) check_output_path(o.output);
    if (settings.aovs && !o.output.empty() && image_format_for(o.output) != ImageFormat::Exr)
        throw Error("--aovs needs an .exr output");
    const bool want_camera = !o.camera.empty() || !o.look_at.empty();
    if (want_camera && (o.camera.empty() || o.look_at.empty()))
        throw Error("--camera and --look-at go together");
    if (o.output.empty() && o.export_ply_path.empty() && !o.print_scene_info && !o.print_memory_info &&
        !o.print_geometry_info)
        throw Error("need -o OUTPUT.png|jpg|exr (see --help)");

    const Clock::time_point start = Clock::now();
    const Scene scene = load_scene(o.scene_path);
    const double load_seconds = seconds_since(start);
    if (o.print_scene_info) print_scene_info(scene, stdout);

    // Facades follow the scene's seed (not --seed, which drives the pixel streams), so every
    // render of a scene shows the same buildings.
    FacadeOptions facades;
    facades.seed = scene.header.seed;
    facades.shop_probability = o.shop_probability;
    const Clock::time_point build_start = Clock::now();
    const std::unique_ptr<RenderScene> render_scene = build_render_scene(scene, modes, facades, ProgressSettings{settings.quiet});
    const double build_seconds = seconds_since(build_start);
    if (o.print_geometry_info) print_geometry_info(*render_scene, stdout);
    // Lamps and lit windows glow once the sun is down (dusk, night, or --sun-elevation below 1).
    const Sky sky = Sky::for_settings(SkySettings{time, o.sun_elevation, o.sun_azimuth, o.moon});
    const bool lights_on = sky.sun_elevation() < kLightsOnBelowElevation;
    if (!lights_on) light_options.lamps = false, light_options.lit_windows = 0;
    const SceneLights lights(scene, facades, light_options);
    if (o.print_geometry_info)
        std::printf("lights: %zu lamps, %zu window strips (%llu of %llu windows lit), %s sampler, %.1f MB\n"
                    "light_lamps: %zu\nlight_window_strips: %zu\nlit_windows: %llu\nwindows: %llu\nlight_bytes: %zu\n",
                    lights.lamp_count(), lights.strip_count(), static_cast<unsigned long long>(lights.lit_window_count()),
                    static_cast<unsigned long long>(lights.window_count()), to_string(light_options.sampler),
                    lights.bytes() / 1e6, lights.lamp_count(), lights.strip_count(),
                    static_cast<unsigned long long>(lights.lit_window_count()),
                    static_cast<unsigned long long>(lights.window_count()), lights.bytes());
    const MaterialTable materials = default_materials();
    if (!o.export_ply_path.empty()) export_ply(*render_scene, materials, o.export_ply_path);
    if (o.output.empty()) {
        if (o.print_memory_info) print_memory_info(*render_scene, stdout);
        if (o.print_memory_info) std::printf("light_bytes: %zu\n", lights.bytes());
        return 0;
    }

    const Camera camera =
        want_camera ? Camera::look_at(parse_point(o.camera, "--camera"), parse_point(o.look_at, "--look-at"), o.fov,
                                      settings.width, settings.height)
                    : framing_camera(scene, o.fov, settings.width, settings.height);
    settings.integrator.fog.density = o.fog;
    settings.integrator.fog.top_z = scene.ground.z + o.fog_height;
    settings.integrator.haze_extinction = o.visibility_km > 0 ? 3.912 / (o.visibility_km * 1000) : 0;
    const PathContext context{*render_scene, materials, sky, settings.integrator, &lights};
    RenderStats stats;
    const Film film = render_image(context, camera, settings, &stats);
    const double exposure = std::isnan(o.exposure_ev) ? auto_exposure(film) : exposure_from_ev(o.exposure_ev);
    const Clock::time_point write_start = Clock::now();
    write_image(film, o.output, exposure);
    const double write_seconds = seconds_since(write_start);

    if (o.print_memory_info) print_memory_info(*render_scene, stdout);
    if (o.print_memory_info) std::printf("light_bytes: %zu\n", lights.bytes());
    if (o.stats) {
        // Phases besides the tracing: loading the file, building geometry and BVH, writing.
        std::printf("load_seconds: %.3f\nbuild_seconds: %.3f\nwrite_seconds: %.3f\n", load_seconds, build_seconds,
                    write_seconds);
        std::printf("render_seconds: %.3f\nrays: %llu\nrays_per_second: %.0f\n", stats.seconds,
                    static_cast<unsigned long long>(stats.rays), stats.rays / std::max(stats.seconds, 1e-9));
        // The view actually used (also the automatic one), so another renderer can match it.
        const Vec3 p = camera.position(), t = camera.position() + camera.forward() * 100;
        std::printf("camera: %.3f,%.3f,%.3f\nlook_at: %.3f,%.3f,%.3f\nfov: %.3f\n", p.x, p.y, p.z, t.x, t.y, t.z, o.fov);
        const Vec3 sun = sky.sun_direction();
        std::printf("sun_direction: %.5f,%.5f,%.5f\nsun_irradiance: %.4f\n", sun.x, sun.y, sun.z,
                    sky.has_sun() ? luminance(sky.sun_radiance()) * sky.sun_solid_angle() : 0.0);
        std::printf("sun_elevation: %.3f\nexposure_ev: %.3f\nlights: %zu\n", sky.sun_elevation(),
                    ev_from_exposure(exposure), lights.sampler().size());
    }
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"render: path-trace a citygen scene with Embree"};
    app.set_version_flag("--version", std::string("citygen render ") + CITYGEN_VERSION);
    Options o;
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
    app.add_option("--max-depth", r.integrator.max_depth, "bounces after the first hit")
        ->check(CLI::Range(0, 1000))->capture_default_str();
    app.add_option("--rr-depth", r.integrator.rr_depth, "bounces always traced before Russian roulette starts")
        ->check(CLI::Range(0, 1000))->capture_default_str();
    app.add_option("--rr-prob", r.integrator.rr_prob,
                   "least survival probability of a roulette step: a path survives with its largest "
                   "throughput component, clamped to [rr-prob, 1], and is reweighted by 1/survival")
        ->check(CLI::Range(0.01, 1.0))->capture_default_str();
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
    app.add_option("--export-ply", o.export_ply_path, "write the stored triangles as binary PLY (material per face)");
    app.add_flag("--print-scene-info", o.print_scene_info, "object counts and bounds");
    app.add_flag("--print-memory-info", o.print_memory_info, "Embree and buffer bytes, peak RSS");
    app.add_flag("--print-scene-geometry-info", o.print_geometry_info, "triangles or primitives per class");
    app.add_flag("--stats", o.stats, "print render_seconds:, rays_per_second: and the camera used");
    app.add_flag("-q,--quiet", r.quiet, "no progress bar");

    try {
        app.parse(argc, argv);
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
