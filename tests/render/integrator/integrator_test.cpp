// The integrator's energy checks: white furnace (with and without Russian roulette), a
// perfect mirror, a closed glass block, and sun sampling against a closed form.
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "render/film/render_image.h"
#include "render/geometry/build_render_scene.h"
#include "tests/render/small_town.h"

using namespace citygen;
using namespace citygen::test;

TEST(WhiteFurnace, DiffuseAlbedoOneUnderUniformSkyIsOneEverywhere) {
    const auto scene = build_render_scene(small_town(), GeometryModes{});
    const MaterialTable materials = all_white_diffuse();
    const Sky sky = Sky::uniform({1, 1, 1});
    const RenderSettings r = tiny(8);
    const Film film = render_image({*scene, materials, sky, r.integrator}, view_of_town(r), r);
    expect_all_one(film);
}

TEST(WhiteFurnace, StaysOneWithRussianRouletteFromTheFirstBounce) {
    // Albedo 1 keeps every path's throughput at 1, so the roulette keeps every path: still exact.
    const auto scene = build_render_scene(small_town(), GeometryModes{});
    const MaterialTable materials = all_white_diffuse();
    const Sky sky = Sky::uniform({1, 1, 1});
    RenderSettings r = tiny(8);
    r.integrator.rr_depth = 0;
    r.integrator.rr_prob = 0.05;
    const Film film = render_image({*scene, materials, sky, r.integrator}, view_of_town(r), r);
    expect_all_one(film);
}

TEST(RussianRoulette, SurvivalFollowsTheThroughputWithinItsBounds) {
    EXPECT_DOUBLE_EQ(russian_roulette_survival({0.3, 0.6, 0.2}, 0.1), 0.6);
    EXPECT_DOUBLE_EQ(russian_roulette_survival({0.01, 0.02, 0.03}, 0.1), 0.1);
    EXPECT_DOUBLE_EQ(russian_roulette_survival({2.0, 0.5, 0.5}, 0.1), 1.0);
}

namespace {

MaterialTable all_diffuse(double albedo) {
    MaterialTable m = default_materials();
    for (Material& x : m) x = Material{"grey", MaterialType::Diffuse, {albedo, albedo, albedo}, {0, 0, 0}, 1, 1.5, {}};
    return m;
}

struct NoisyRender {
    double mean = 0;   // over pixels and channels
    double noise = 0;  // variance of one pixel's estimate, from two seeds: mean of (a - b)^2 / 2
    uint64_t rays = 0;
};

NoisyRender render_twice(const RenderScene& scene, const MaterialTable& materials, RenderSettings r,
                         const Sky& sky = Sky::uniform({1, 1, 1})) {
    RenderStats stats;
    r.seed = 1;
    const Film a = render_image({scene, materials, sky, r.integrator}, view_of_town(r), r, &stats);
    r.seed = 2;
    const Film b = render_image({scene, materials, sky, r.integrator}, view_of_town(r), r);
    NoisyRender out;
    for (size_t i = 0; i < a.rgb.size(); ++i) {
        out.mean += (a.rgb[i] + b.rgb[i]) / 2;
        out.noise += (a.rgb[i] - b.rgb[i]) * (a.rgb[i] - b.rgb[i]) / 2;
    }
    out.mean /= a.rgb.size();
    out.noise /= a.rgb.size();
    out.rays = stats.rays;
    return out;
}

}  // namespace

TEST(RussianRoulette, UnbiasedAndCheaperOnAGreyTown) {
    const auto scene = build_render_scene(small_town(), GeometryModes{});
    const MaterialTable materials = all_diffuse(0.5);
    const NoisyRender off = render_twice(*scene, materials, tiny(32));
    RenderSettings r = tiny(32);
    r.integrator.rr_depth = 0;
    r.integrator.rr_prob = 0.05;
    const NoisyRender on = render_twice(*scene, materials, r);
    // Standard error of the difference of the two image means (2 seeds x pixels x channels).
    const double samples = 2.0 * 3 * r.width * r.height;
    const double standard_error = std::sqrt((off.noise + on.noise) / samples);
    EXPECT_NEAR(on.mean, off.mean, 4 * standard_error + 1e-3);
    EXPECT_LT(on.rays, off.rays * 0.95) << "the roulette should end some dim paths";
}

TEST(RussianRoulette, AddsLittleNoiseOnNearlyWhiteWalls) {
    // The render engineer's case: light walls in sunlight and a low survival probability. With
    // a fixed probability 0.1 survivors' weights grow by 9.5x per bounce and the noise explodes;
    // with throughput-based survival the roulette costs little noise.
    const auto scene = build_render_scene(small_town(), GeometryModes{});
    const MaterialTable materials = all_diffuse(0.95);
    const Sky sky = Sky::daylight(TimeOfDay::Day);
    const NoisyRender off = render_twice(*scene, materials, tiny(16), sky);
    RenderSettings r = tiny(16);
    r.integrator.rr_depth = 0;
    r.integrator.rr_prob = 0.1;
    const NoisyRender on = render_twice(*scene, materials, r, sky);
    // Measured: about 1.6x the noise without roulette (a fixed 0.1 gave 93x, a fixed 0.6 gave 7x).
    EXPECT_LT(on.noise, 2.5 * off.noise) << "noise with roulette " << on.noise << ", without " << off.noise;
    EXPECT_LT(on.rays, off.rays);
}

TEST(Mirror, ReflectanceOneShowsTheSkyUnchanged) {
    Scene s;  // only the ground plane, made a perfect mirror
    s.ground.min = {-100, -100};
    s.ground.max = {100, 100};
    const auto scene = build_render_scene(s, GeometryModes{});
    MaterialTable materials = default_materials();
    materials[kGround] = materials[kMirror];
    const Sky sky = Sky::daylight(TimeOfDay::Day);
    const PathContext context{*scene, materials, sky, IntegratorSettings{}};
    Rng rng(7);
    int checked = 0;
    for (int i = 0; i < 200; ++i) {
        const double phi = 2 * kPi * rng.next_double();
        const double down = -(0.05 + 0.9 * rng.next_double());
        const Vec3 dir = normalize(Vec3{std::cos(phi), std::sin(phi), down});
        const Vec3 reflected{dir.x, dir.y, -dir.z};
        if (sky.in_sun_disc(reflected)) continue;
        uint64_t rays = 0;
        const Color seen = trace_path(context, Ray{{0, 0, 10}, dir, 0, 1e30}, rng, rays);
        const Color expected = sky.radiance(reflected);
        for (int c = 0; c < 3; ++c) EXPECT_NEAR(seen[c], expected[c], 1e-4 * expected[c] + 1e-7);
        EXPECT_EQ(rays, 2u);
        ++checked;
    }
    EXPECT_GT(checked, 150);
}

TEST(Glass, ClosedGlassBlockNeitherCreatesNorLosesEnergy) {
    Scene s = small_town();
    s.buildings[1].min_height = 4;  // floating: closed by its underside
    const auto scene = build_render_scene(s, GeometryModes{});
    MaterialTable materials = all_white_diffuse();
    materials[kFacade] = default_materials()[kGlass];
    materials[kRoof] = default_materials()[kGlass];
    const Sky sky = Sky::uniform({1, 1, 1});
    const RenderSettings r = tiny(8);
    const Film film = render_image({*scene, materials, sky, r.integrator}, view_of_town(r), r);
    expect_all_one(film);
}

// A diffuse plane under a uniform sky and a large sun has a closed-form radiance:
// albedo * (L_sky + L_sun * pi sin^2(radius) * cos(sun zenith) / pi). Next-event estimation
// with MIS and pure BSDF sampling must both converge to it (a wrong MIS weight would not).
TEST(SunSampling, NextEventWithMisAndBsdfSamplingAgreeWithTheClosedForm) {
    Scene s;
    s.ground.min = {-100, -100};
    s.ground.max = {100, 100};
    const auto scene = build_render_scene(s, GeometryModes{});
    MaterialTable materials = default_materials();
    const double albedo = 0.5, sky_radiance = 0.2, radius = 8 * kPi / 180, sun = 40;
    materials[kGround] = Material{"grey", MaterialType::Diffuse, {albedo, albedo, albedo}, {}, 1, 1.5, {}};
    const Vec3 sun_direction = normalize(Vec3{0.3, -0.5, 0.7});
    const Sky sky = Sky::uniform_with_sun({sky_radiance, sky_radiance, sky_radiance}, sun_direction, radius,
                                          {sun, sun, sun});
    const double expected = albedo * (sky_radiance + sun * std::pow(std::sin(radius), 2) * sun_direction.z);
    RenderSettings r = tiny(64);
    r.width = r.height = 32;
    r.integrator = IntegratorSettings{};
    const Camera camera = Camera::look_at({0, 0, 20}, {0, 0, 0}, 40, r.width, r.height);  // sees only the plane
    for (bool next_event : {true, false}) {
        r.integrator.sample_sun = next_event;
        const Film film = render_image({*scene, materials, sky, r.integrator}, camera, r);
        const ChannelStats st = stats_of(film, 1);
        // Tight enough that a doubled or missing sun (weights summing to 2 or 0) cannot pass.
        EXPECT_LT(st.standard_error, (next_event ? 0.005 : 0.04) * expected) << "next event " << next_event;
        EXPECT_NEAR(st.mean, expected, 4 * st.standard_error + 0.002 * expected) << "next event " << next_event;
    }
}

