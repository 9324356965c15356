// Unidirectional path tracing with next-event estimation of the sun and multiple importance
// sampling (power heuristic) against BSDF sampling; throughput-based Russian roulette after
// rr_depth bounces.
#pragma once

#include <cstdint>

#include "common/rng.h"
#include "render/facade/building_looks.h"
#include "render/integrator/fog.h"
#include "render/lights/sky.h"
#include "render/materials/materials.h"
#include "render/scene/render_scene.h"

namespace citygen {

struct IntegratorSettings {
    int max_depth = 8;       // bounces after the first hit (0: direct light only)
    int rr_depth = 3;        // bounces always traced; Russian roulette decides on every later one
    double rr_prob = 0.8;    // least survival probability of a roulette step (see russian_roulette_survival)
    bool sample_sun = true;  // next-event estimation; false leaves the sun to BSDF sampling alone
    bool sample_lights = true;  // next-event estimation of lamps and windows; false: BSDF sampling alone
    FogSettings fog;              // --fog: ground fog scattering sun, moon and lamp light (fog.h)
    double haze_extinction = 0;   // aerial perspective on camera rays, 1/m (3.912 / visibility); 0: none
    // Lamp and window samples whose unshadowed contribution (luminance, render units) is below
    // this trace their shadow ray with probability contribution / shadow_roulette and count
    // 1 / that if it passes (Russian roulette: unbiased). 0: every shadow ray is traced.
    double shadow_roulette = 0;
    // Path vertices whose throughput (luminance, 1 at the camera) is below this sample a lamp or
    // window with probability throughput / light_sampling_throughput, and an emitter hit after
    // such a vertex is weighted against that probability times the light's pdf (multiple
    // importance sampling with a stochastic strategy: unbiased). Deep, dim vertices then mostly
    // skip the light-tree descent, whose cost does not shrink with their share of the picture.
    // 0: every vertex samples a light. 0.3 gave the least error per CPU second on the night
    // street view of tests/bench/night_bench.sh (docs/bench/2026-11-night.md, third round).
    double light_sampling_throughput = 0.3;
};

// The shadow_roulette for a displayed image with this exposure: contributions below 0.03 of
// the tone curve's input (white is near 10), a 300th of white, which at night are most of the
// windows' and far lamps' samples. A lower threshold saves less CPU, a higher one adds visible
// error (tests/bench/night_bench.sh; docs/bench/2026-11-night.md, cheaper night samples).
double shadow_roulette_for(double exposure);

class SceneLights;
class SmallEmitters;

struct PathContext {
    const RenderScene& scene;
    const MaterialTable& materials;
    const Sky& sky;
    IntegratorSettings settings;
    const BuildingLooks* building_looks = nullptr;  // buildings' own colours and patterns (none: stock)
    const SceneLights* lights = nullptr;  // lamps and lit windows (lights/scene_lights.h); none if null
    // Lamp globes and lit panes whose light the film gathers itself (small_emitters.h): camera
    // rays that hit one count no emission. render_image sets it for its camera; none if null.
    const SmallEmitters* small_emitters = nullptr;
};

// Survival probability of a Russian roulette step: the path's largest throughput component,
// at most 1 and at least min_survival (--rr-prob). A path that still carries much light is kept,
// a dim one is cut, and a survivor's throughput divided by this probability stays bounded (about
// 1, or 1 / min_survival), so the roulette adds little variance even on white walls. A fixed
// probability below the albedo would let survivors' weights grow without bound.
double russian_roulette_survival(Color throughput, double min_survival);

// Random numbers for a path's first surface, stratified over a pixel's samples (render_image):
// the light choice, the point on the light and the window on a strip (0-3), the roulettes (4),
// the BSDF sample (5-7).
struct FirstVertexNumbers {
    double u[8];
};

// Radiance arriving along `ray`. `rays` counts every ray traced (closest hit and shadow).
// `first`, if given, replaces the stream's numbers at the first surface.
Color trace_path(const PathContext& context, Ray ray, Rng& rng, uint64_t& rays,
                 const FirstVertexNumbers* first = nullptr);

// The aerial haze's colour along a camera ray: the sky's colour low in the ray's azimuth, which
// distant ground fades into.
Color horizon_haze(const Sky& sky, Vec3 direction);

// The smooth part of what a camera ray that leaves the scene shows, free of noise: the sky
// without its stars and sun disc or, below the horizon with haze on, the haze the ground past
// the plane's edge would show. (Stars and the disc are smaller than a pixel's samples resolve.)
Color smooth_sky_seen(const PathContext& context, Vec3 direction);

// Moves a ray origin off the surface along `normal` by a distance that covers float error at
// city coordinates (a few hundred micrometres at 2 km from the origin).
Vec3 offset_origin(Vec3 position, Vec3 normal);

}  // namespace citygen
