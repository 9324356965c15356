// How close a render comes to Embree's own speed (issue 25 §4, run by hand, not by ctest;
// tests/bench/ray_limit.sh runs it on Monaco). Loads a scene, builds it as render does, renders
// once with a RayRecorder attached to get the render's ray population, then times, in turn,
// the render itself (recorder detached) and a replay of the recorded rays through the same
// Embree scene with no shading at all: rtcIntersect1 / rtcOccluded1 per ray, on every core, each
// thread's rays in the order it traced them, split into chunks of a tile's worth of rays as the
// render splits its tiles. The ratio of the two rates is what the render spends beside Embree
// (and, in procedural mode, beside our own intersection callbacks, which the replay calls too).
// It also replays the shadow rays alone, one at a time, in packets of 4, 8 and 16
// (rtcOccluded4/8/16, consecutive shadow rays of a thread) and as a stream (rtcOccluded1M), to
// see whether packets would pay.
//
//   ray_limit SCENE [render's view, sky, light, integrator and geometry options] [--repeat N]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <tbb/blocked_range.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include "common/error.h"
#include "common/scene_io.h"
#include "render/film/render_image.h"
#include "render/geometry/build_render_scene.h"
#include "render/geometry/ground.h"
#include "render/options.h"
#include "render/production/render_frames.h"
#include "render/scene/ray_recorder.h"

using namespace citygen;

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n == 0 ? 0 : n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// A run of consecutive rays of one thread's list.
struct Chunk {
    const RecordedRay* rays;
    size_t count;
};

std::vector<Chunk> split(const std::vector<std::vector<RecordedRay>>& lists, size_t chunk_rays) {
    std::vector<Chunk> chunks;
    for (const auto& list : lists)
        for (size_t i = 0; i < list.size(); i += chunk_rays)
            chunks.push_back({list.data() + i, std::min(chunk_rays, list.size() - i)});
    return chunks;
}

RTCRay embree_ray(const RecordedRay& r) {
    RTCRay ray;
    ray.org_x = r.origin[0], ray.org_y = r.origin[1], ray.org_z = r.origin[2];
    ray.dir_x = r.direction[0], ray.dir_y = r.direction[1], ray.dir_z = r.direction[2];
    ray.tnear = r.tnear, ray.tfar = r.tfar;
    ray.time = 0, ray.mask = 0xFFFFFFFFu, ray.id = 0, ray.flags = 0;
    return ray;
}

// Traces one recorded ray as the render did, with no shading; returns whether it hit.
bool trace_one(RTCScene scene, const RecordedRay& r) {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    if (r.kind == RayKind::Shadow) {
        RTCRay ray = embree_ray(r);
        rtcOccluded1(scene, &context, &ray);
        return ray.tfar < 0;
    }
    RTCRayHit rh;
    rh.ray = embree_ray(r);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene, &context, &rh);
    return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
}

// What a replay traced and how many of its answers differ from the render's (must be none).
struct Replay {
    double seconds = 0;
    uint64_t rays = 0, mismatches = 0;
};

// Runs trace(chunk, rays, mismatches) over the chunks in parallel, a chunk a task.
template <class Trace>
Replay replay(const std::vector<Chunk>& chunks, Trace trace) {
    struct Counts {
        uint64_t rays = 0, mismatches = 0;
    };
    const Clock::time_point start = Clock::now();
    const Counts total = tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, chunks.size(), 1), Counts{},
        [&](const tbb::blocked_range<size_t>& range, Counts counts) {
            for (size_t c = range.begin(); c != range.end(); ++c) trace(chunks[c], counts.rays, counts.mismatches);
            return counts;
        },
        [](Counts a, Counts b) { return Counts{a.rays + b.rays, a.mismatches + b.mismatches}; });
    return {seconds_since(start), total.rays, total.mismatches};
}

Replay replay_all(RTCScene scene, const std::vector<Chunk>& chunks) {
    return replay(chunks, [scene](const Chunk& chunk, uint64_t& rays, uint64_t& mismatches) {
        for (size_t i = 0; i < chunk.count; ++i) mismatches += trace_one(scene, chunk.rays[i]) != chunk.rays[i].hit;
        rays += chunk.count;
    });
}

template <int N> struct Packet;
template <> struct Packet<4> { using type = RTCRay4; };
template <> struct Packet<8> { using type = RTCRay8; };
template <> struct Packet<16> { using type = RTCRay16; };

void occluded_packet(const int* valid, RTCScene s, RTCIntersectContext* c, RTCRay4* r) { rtcOccluded4(valid, s, c, r); }
void occluded_packet(const int* valid, RTCScene s, RTCIntersectContext* c, RTCRay8* r) { rtcOccluded8(valid, s, c, r); }
void occluded_packet(const int* valid, RTCScene s, RTCIntersectContext* c, RTCRay16* r) { rtcOccluded16(valid, s, c, r); }

// The shadow rays of each chunk, N at a time in their order (width 1: rtcOccluded1).
template <int N>
Replay replay_shadow_packets(RTCScene scene, const std::vector<Chunk>& chunks) {
    return replay(chunks, [scene](const Chunk& chunk, uint64_t& rays, uint64_t& mismatches) {
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        typename Packet<N>::type packet;
        alignas(64) int valid[N];
        const RecordedRay* members[N];
        int filled = 0;
        auto flush = [&] {
            for (int k = filled; k < N; ++k) valid[k] = 0;
            occluded_packet(valid, scene, &context, &packet);
            for (int k = 0; k < filled; ++k) mismatches += (packet.tfar[k] < 0) != members[k]->hit;
            rays += filled;
            filled = 0;
        };
        for (size_t i = 0; i < chunk.count; ++i) {
            const RecordedRay& r = chunk.rays[i];
            if (r.kind != RayKind::Shadow) continue;
            packet.org_x[filled] = r.origin[0], packet.org_y[filled] = r.origin[1], packet.org_z[filled] = r.origin[2];
            packet.dir_x[filled] = r.direction[0], packet.dir_y[filled] = r.direction[1];
            packet.dir_z[filled] = r.direction[2];
            packet.tnear[filled] = r.tnear, packet.tfar[filled] = r.tfar;
            packet.time[filled] = 0, packet.mask[filled] = 0xFFFFFFFFu, packet.id[filled] = 0, packet.flags[filled] = 0;
            valid[filled] = -1;
            members[filled++] = &r;
            if (filled == N) flush();
        }
        if (filled > 0) flush();
    });
}

Replay replay_shadow_singles(RTCScene scene, const std::vector<Chunk>& chunks) {
    return replay(chunks, [scene](const Chunk& chunk, uint64_t& rays, uint64_t& mismatches) {
        for (size_t i = 0; i < chunk.count; ++i) {
            if (chunk.rays[i].kind != RayKind::Shadow) continue;
            mismatches += trace_one(scene, chunk.rays[i]) != chunk.rays[i].hit;
            ++rays;
        }
    });
}

// All shadow rays of a chunk in one rtcOccluded1M call, marked coherent (Embree may then sort
// them into packets itself).
Replay replay_shadow_stream(RTCScene scene, const std::vector<Chunk>& chunks) {
    return replay(chunks, [scene](const Chunk& chunk, uint64_t& rays, uint64_t& mismatches) {
        std::vector<RTCRay> stream;
        std::vector<const RecordedRay*> members;
        for (size_t i = 0; i < chunk.count; ++i)
            if (chunk.rays[i].kind == RayKind::Shadow) {
                stream.push_back(embree_ray(chunk.rays[i]));
                members.push_back(&chunk.rays[i]);
            }
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        rtcOccluded1M(scene, &context, stream.data(), static_cast<unsigned>(stream.size()), sizeof(RTCRay));
        for (size_t k = 0; k < stream.size(); ++k) mismatches += (stream[k].tfar < 0) != members[k]->hit;
        rays += stream.size();
    });
}

// What the bench was asked beyond render's own options.
struct BenchOptions {
    int repeat = 3;
    bool packets = false;
    std::string label;
};

// Everything render builds before it traces, in render's order (render/main.cpp).
struct World {
    Scene scene;
    std::unique_ptr<RenderScene> render_scene;
    std::unique_ptr<Sky> sky;
    std::unique_ptr<SceneLights> lights;
    MaterialTable materials;
    std::unique_ptr<BuildingLooks> looks;
    std::unique_ptr<Camera> camera;
    RenderSettings settings;
    double exposure = 1;
    PathContext context() const { return {*render_scene, materials, *sky, settings.integrator, looks.get(), lights.get()}; }
};

std::unique_ptr<World> build_world(const Options& o) {
    const Job job = prepare_view_job(o);
    auto w = std::make_unique<World>();
    w->settings = job.settings;
    w->settings.quiet = true;
    w->scene = load_scene(o.scene_path);
    sink_field_under_sea(w->scene);
    const FacadeOptions facades = facade_options(o, w->scene);
    w->render_scene = build_render_scene(w->scene, job.modes, facades, ProgressSettings{true});
    w->sky = std::make_unique<Sky>(make_sky(o, job));
    w->lights = std::make_unique<SceneLights>(w->scene, facades, lights_under(*w->sky, job.lights));
    w->materials = default_materials();
    w->camera = std::make_unique<Camera>(view_camera(o, job, w->scene));
    set_atmosphere(o, w->scene, w->settings.integrator);
    w->looks = std::make_unique<BuildingLooks>(w->scene);
    w->exposure = view_exposure(o, w->context(), *w->camera, w->settings);
    return w;
}

// The render as render does it (no denoiser): its rays and the wall time of the trace.
RenderStats render_once(const World& w) {
    RenderStats stats;
    render_view(w.context(), *w.camera, w.settings, false, w.exposure, &stats);
    return stats;
}

int tile_count(const RenderSettings& s) {
    const PixelRegion r = render_region(s);
    return ((r.width() + 15) / 16) * ((r.height() + 15) / 16);
}

std::string mode_name(const Options& o) {
    std::string name = o.procedural ? "procedural" : "stored";
    for (int c = 0; c < kGeometryClassCount; ++c)
        if (!o.geometry[c].empty()) name += std::string(",") + to_string(static_cast<GeometryClass>(c)) + "=" + o.geometry[c];
    return name;
}

double mrays(uint64_t rays, double seconds) { return rays / std::max(seconds, 1e-9) / 1e6; }

void print_shadow_packets(RTCScene scene, const std::vector<Chunk>& chunks, int repeat) {
    std::vector<double> singles, p4, p8, p16, stream;
    uint64_t rays = 0, mismatches = 0;
    for (int i = 0; i < repeat; ++i) {
        auto add = [&](const Replay& r, std::vector<double>& to) {
            to.push_back(mrays(r.rays, r.seconds));
            rays = r.rays;
            mismatches += r.mismatches;
        };
        add(replay_shadow_singles(scene, chunks), singles);
        add(replay_shadow_packets<4>(scene, chunks), p4);
        add(replay_shadow_packets<8>(scene, chunks), p8);
        add(replay_shadow_packets<16>(scene, chunks), p16);
        add(replay_shadow_stream(scene, chunks), stream);
    }
    std::printf("shadow rays alone, Mrays/s (median of %d): %llu rays; 1 at a time %.2f, x4 %.2f, x8 %.2f, x16 %.2f, "
                "stream %.2f; mismatches %llu\n",
                repeat, static_cast<unsigned long long>(rays), median(singles), median(p4), median(p8), median(p16),
                median(stream), static_cast<unsigned long long>(mismatches));
}

int run(const Options& o, const BenchOptions& bench) {
    const std::unique_ptr<World> world = build_world(o);
    RayRecorder recorder;
    world->render_scene->set_ray_recorder(&recorder);
    const RenderStats recorded = render_once(*world);
    world->render_scene->set_ray_recorder(nullptr);
    if (recorder.count() != recorded.rays)
        std::fprintf(stderr, "ray_limit: note: recorded %llu rays, the render counted %llu\n",
                     static_cast<unsigned long long>(recorder.count()), static_cast<unsigned long long>(recorded.rays));
    const auto lists = recorder.thread_lists();
    const size_t chunk_rays = std::max<size_t>(1, recorder.count() / tile_count(world->settings));
    const std::vector<Chunk> chunks = split(lists, chunk_rays);
    const RTCScene scene = world->render_scene->embree_scene();

    // Interleaved, so a drift of the shared machine's speed hits both alike; ratio per pair.
    std::vector<double> ours, replayed, ratios;
    uint64_t mismatches = 0;
    for (int i = 0; i < bench.repeat; ++i) {
        const RenderStats render = render_once(*world);
        const Replay replay = replay_all(scene, chunks);
        mismatches += replay.mismatches;
        ours.push_back(mrays(render.rays, render.seconds));
        replayed.push_back(mrays(replay.rays, replay.seconds));
        ratios.push_back(ours.back() / replayed.back());
    }
    std::printf("| %s | %s | %dx%d %d spp | %.2f M (camera %.2f, bounce %.2f, shadow %.2f) | %.2f | %.2f | %.2f |\n",
                bench.label.empty() ? mode_name(o).c_str() : bench.label.c_str(), o.time.c_str(), world->settings.width,
                world->settings.height, world->settings.spp, recorder.count() / 1e6,
                recorder.count(RayKind::Camera) / 1e6, recorder.count(RayKind::Bounce) / 1e6,
                recorder.count(RayKind::Shadow) / 1e6, median(ours), median(replayed), median(ratios));
    if (mismatches) std::fprintf(stderr, "ray_limit: %llu replayed rays disagree with the render\n",
                                 static_cast<unsigned long long>(mismatches));
    if (bench.packets) print_shadow_packets(scene, chunks, bench.repeat);
    return mismatches ? 1 : 0;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"ray_limit: a render's rays/s against Embree's on the same rays with no shading"};
    Options o;
    BenchOptions bench;
    app.add_option("scene", o.scene_path, "scene file written by osmparse")->required();
    app.add_option("--threads", o.threads, "worker threads (0: all cores)");
    app.add_option("--repeat", bench.repeat, "timed render/replay pairs (the median is printed)")->capture_default_str();
    app.add_flag("--packets", bench.packets, "also replay the shadow rays alone in packets and streams");
    app.add_option("--label", bench.label, "the table's first column (default: the geometry mode)");
    add_view_options(app, o);
    add_sky_and_light_options(app, o);
    add_integrator_options(app, o);
    add_geometry_mode_options(app, o);
    CLI11_PARSE(app, argc, argv);
    try {
        std::unique_ptr<tbb::global_control> limit;
        if (o.threads > 0)
            limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, o.threads);
        return run(o, bench);
    } catch (const Error& e) {
        std::fprintf(stderr, "ray_limit: %s\n", e.what());
        return 1;
    }
}
