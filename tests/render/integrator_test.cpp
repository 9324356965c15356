// The renderer as a library: energy checks of the integrator (white furnace, mirror, glass),
// determinism across thread counts, stored geometry and its hit table.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <tuple>
#include <memory>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "bsdf.h"
#include "error.h"
#include "build_render_scene.h"
#include "render_image.h"
#include "stored_geometry.h"
#include "triangulate_polygon.h"

using namespace citygen;

namespace {

Ring square(double x0, double y0, double size) {
    return {{x0, y0}, {x0 + size, y0}, {x0 + size, y0 + size}, {x0, y0 + size}};
}

// A courtyard building (concave: light bounces between its walls) and a plain block.
Scene small_town() {
    Scene s;
    s.header.bounds_min = {-50, -50};
    s.header.bounds_max = {50, 50};
    s.ground.min = {-50, -50};
    s.ground.max = {50, 50};
    Building courtyard;
    courtyard.outer = square(-20, -20, 30);
    Ring hole = square(-12, -12, 14);
    std::reverse(hole.begin(), hole.end());
    courtyard.holes.push_back(hole);
    courtyard.height = 18;
    s.buildings.push_back(courtyard);
    Building block;
    block.outer = square(15, 5, 10);
    block.height = 30;
    s.buildings.push_back(block);
    RoadEdge road;
    road.quad = {{-50, -30}, {50, -30}, {50, -24}, {-50, -24}};
    s.roads.push_back(road);
    Sidewalk walk;
    walk.polygon = {{-50, -24}, {50, -24}, {50, -22}, {-50, -22}};
    s.sidewalks.push_back(walk);
    return s;
}

MaterialTable all_white_diffuse() {
    MaterialTable m = default_materials();
    for (Material& x : m) x = Material{"white", MaterialType::Diffuse, {1, 1, 1}, {0, 0, 0}, 1, 1.5, {}};
    return m;
}

RenderSettings tiny(int spp) {
    RenderSettings r;
    r.width = 24;
    r.height = 16;
    r.spp = spp;
    r.quiet = true;
    r.integrator.max_depth = 1000;
    r.integrator.rr_depth = 1000;  // no roulette: every path carries exactly its throughput
    return r;
}

Camera view_of_town(const RenderSettings& r) {
    return Camera::look_at({-60, -70, 45}, {0, 0, 5}, 60, r.width, r.height);
}

struct ChannelStats {
    double mean = 0, standard_error = 0, min = 1e30, max = -1e30;
};

ChannelStats stats_of(const Film& film, int channel) {
    ChannelStats s;
    const size_t n = film.rgb.size() / 3;
    double sum = 0, sum2 = 0;
    for (size_t i = 0; i < n; ++i) {
        const double v = film.rgb[3 * i + channel];
        sum += v;
        sum2 += v * v;
        s.min = std::min(s.min, v);
        s.max = std::max(s.max, v);
    }
    s.mean = sum / n;
    s.standard_error = std::sqrt(std::max(0.0, sum2 / n - s.mean * s.mean) / n);
    return s;
}

}  // namespace

TEST(WhiteFurnace, DiffuseAlbedoOneUnderUniformSkyIsOneEverywhere) {
    const auto scene = build_render_scene(small_town(), GeometryModes{});
    const MaterialTable materials = all_white_diffuse();
    const Sky sky = Sky::uniform({1, 1, 1});
    const RenderSettings r = tiny(8);
    const Film film = render_image({*scene, materials, sky, r.integrator}, view_of_town(r), r);
    for (int c = 0; c < 3; ++c) {
        const ChannelStats s = stats_of(film, c);
        EXPECT_NEAR(s.min, 1.0, 0.01) << "channel " << c;
        EXPECT_NEAR(s.max, 1.0, 0.01) << "channel " << c;
    }
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
    for (int c = 0; c < 3; ++c) {
        const ChannelStats s = stats_of(film, c);
        EXPECT_NEAR(s.min, 1.0, 0.01) << "channel " << c;
        EXPECT_NEAR(s.max, 1.0, 0.01) << "channel " << c;
    }
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

TEST(SceneBuild, ShowsGeometryAndBvhProgressUnlessQuiet) {
    // Shown from the start here (show_after 0) so a tiny scene exercises what Monaco needs.
    for (const GeometryMode mode : {GeometryMode::Stored, GeometryMode::Procedural}) {
        testing::internal::CaptureStderr();
        build_render_scene(small_town(), GeometryModes::all(mode), FacadeOptions{}, ProgressSettings{false, 0.0});
        const std::string shown = testing::internal::GetCapturedStderr();
        EXPECT_NE(shown.find("geometry ["), std::string::npos) << shown;
        EXPECT_NE(shown.find("BVH ["), std::string::npos) << shown;
        EXPECT_NE(shown.find("100.0%"), std::string::npos) << shown;
        testing::internal::CaptureStderr();
        build_render_scene(small_town(), GeometryModes::all(mode), FacadeOptions{}, ProgressSettings{true, 0.0});
        EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
    }
}

TEST(Sampling, DirectionsAreContinuousInTheNormalAcrossWalls) {
    // A wall normal with z = +1e-12 or -1e-12 (one rounding apart, e.g. stored triangle vs
    // procedural wall) must scatter the same random numbers into nearly the same direction.
    Material diffuse{"white", MaterialType::Diffuse, {1, 1, 1}, {0, 0, 0}, 1, 1.5, {}};
    Material glossy = diffuse;
    glossy.type = MaterialType::Glossy;
    glossy.specular = {0.5, 0.5, 0.5};
    glossy.exponent = 50;
    for (const Material& m : {diffuse, glossy}) {
        for (double azimuth = 0; azimuth < 6.28; azimuth += 0.1) {
            const Vec3 up = normalize(Vec3{std::cos(azimuth), std::sin(azimuth), 1e-12});
            const Vec3 down = normalize(Vec3{std::cos(azimuth), std::sin(azimuth), -1e-12});
            const Vec3 wo = normalize(up + Vec3{0.2, -0.1, 0.4});
            for (double u : {0.1, 0.37, 0.62, 0.9}) {
                BsdfSample a, b;
                const bool ok_a = bsdf_sample(m, up, wo, u, 1 - u, u * u, a);
                const bool ok_b = bsdf_sample(m, down, wo, u, 1 - u, u * u, b);
                ASSERT_EQ(ok_a, ok_b);
                if (ok_a) {
                    EXPECT_LT(length(a.wi - b.wi), 1e-6) << m.name << " azimuth " << azimuth << " u " << u;
                }
            }
        }
    }
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
        const double phi = 2 * 3.14159265358979 * rng.next_double();
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
    for (int c = 0; c < 3; ++c) {
        const ChannelStats st = stats_of(film, c);
        EXPECT_NEAR(st.min, 1.0, 0.01);
        EXPECT_NEAR(st.max, 1.0, 0.01);
    }
}

TEST(Glass, FresnelReflectsMoreAtGrazingAngles) {
    const Material glass = default_materials()[kGlass];
    const Vec3 n{0, 0, 1};
    auto reflected_fraction = [&](Vec3 wo) {
        int reflected = 0;
        for (int i = 0; i < 2000; ++i) {
            BsdfSample s;
            EXPECT_TRUE(bsdf_sample(glass, n, wo, 0.5, 0.5, (i + 0.5) / 2000, s));
            if (s.wi.z > 0) ++reflected;
        }
        return reflected / 2000.0;
    };
    EXPECT_NEAR(reflected_fraction({0, 0, 1}), 0.04, 0.002);  // ((1.5-1)/(1.5+1))^2
    EXPECT_GT(reflected_fraction(normalize(Vec3{1, 0, 0.05})), 0.5);
    // From inside beyond the critical angle: total internal reflection.
    EXPECT_EQ(reflected_fraction(normalize(Vec3{1, 0, -0.3})), 0.0);  // wi stays inside (z < 0)
}

TEST(Determinism, SameSeedGivesIdenticalPixelsWithOneOrTwoThreads) {
    const auto scene = build_render_scene(small_town(), GeometryModes{});
    const MaterialTable materials = default_materials();
    const Sky sky = Sky::daylight(TimeOfDay::Sunset);
    RenderSettings r = tiny(4);
    r.width = 40;  // several tiles
    r.height = 36;
    r.integrator = IntegratorSettings{};
    const PathContext context{*scene, materials, sky, r.integrator};
    Film one, two;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = render_image(context, view_of_town(r), r);
    }
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
        two = render_image(context, view_of_town(r), r);
    }
    ASSERT_EQ(one.rgb.size(), two.rgb.size());
    EXPECT_EQ(0, std::memcmp(one.rgb.data(), two.rgb.data(), one.rgb.size() * sizeof(float)));
    r.seed = 2;
    const Film other_seed = render_image(context, view_of_town(r), r);
    EXPECT_NE(0, std::memcmp(one.rgb.data(), other_seed.rgb.data(), one.rgb.size() * sizeof(float)));
}

TEST(StoredGeometry, HitsReportObjectKindIndexAndOutwardNormal) {
    const Scene s = small_town();
    const auto scene = build_render_scene(s, GeometryModes{});
    Hit hit;
    // Down onto the tall block's roof.
    ASSERT_TRUE(scene->intersect(Ray{{20, 10, 100}, {0, 0, -1}, 0, 1e30}, hit));
    EXPECT_EQ(hit.kind, ObjectKind::Building);
    EXPECT_EQ(hit.object, 1u);
    EXPECT_EQ(hit.material, kRoof);
    EXPECT_NEAR(hit.t, 70, 1e-3);
    EXPECT_NEAR(hit.geometric_normal.z, 1, 1e-9);
    // Westwards into the courtyard's inner wall (a hole ring): its normal faces the courtyard.
    ASSERT_TRUE(scene->intersect(Ray{{-5, -5, 5}, {-1, 0, 0}, 0, 1e30}, hit));
    EXPECT_EQ(hit.kind, ObjectKind::Building);
    EXPECT_EQ(hit.object, 0u);
    EXPECT_EQ(hit.material, kFacade);
    EXPECT_NEAR(hit.t, 7, 1e-3);
    EXPECT_NEAR(hit.geometric_normal.x, 1, 1e-9);
    // The courtyard has no roof: straight down from above lands on the ground.
    ASSERT_TRUE(scene->intersect(Ray{{-5, -5, 100}, {0, 0, -1}, 0, 1e30}, hit));
    EXPECT_EQ(hit.kind, ObjectKind::Terrain);
    // Road and raised sidewalk with its curb.
    ASSERT_TRUE(scene->intersect(Ray{{0, -27, 10}, {0, 0, -1}, 0, 1e30}, hit));
    EXPECT_EQ(hit.kind, ObjectKind::Road);
    EXPECT_EQ(hit.material, kAsphalt);
    ASSERT_TRUE(scene->intersect(Ray{{0, -23, 10}, {0, 0, -1}, 0, 1e30}, hit));
    EXPECT_EQ(hit.kind, ObjectKind::Sidewalk);
    EXPECT_NEAR(hit.position.z, kRoadLift + 0.15, 1e-4);
    ASSERT_TRUE(scene->intersect(Ray{{0, -27, 0.1}, {0, 1, 0}, 0, 1e30}, hit));
    EXPECT_EQ(hit.kind, ObjectKind::Sidewalk);
    EXPECT_EQ(hit.material, kCurb);
    EXPECT_NEAR(hit.geometric_normal.y, -1, 1e-9);
}

TEST(StoredGeometry, RoofWithHoleCoversExactlyTheRingArea) {
    const Ring outer = square(0, 0, 10);
    Ring hole = square(3, 3, 4);
    std::reverse(hole.begin(), hole.end());
    // An L-shape (non-convex) in the outer ring too.
    const Ring l_shape = {{0, 0}, {10, 0}, {10, 4}, {4, 4}, {4, 10}, {0, 10}};
    for (const auto& [ring, holes, area] : {std::make_tuple(outer, std::vector<Ring>{hole}, 100.0 - 16.0),
                                            std::make_tuple(l_shape, std::vector<Ring>{}, 64.0)}) {
        const PolygonTriangulation t = triangulate_polygon(ring, holes);
        double sum = 0;
        for (const auto& tri : t.triangles) {
            const double a = 0.5 * cross(t.points[tri[1]] - t.points[tri[0]], t.points[tri[2]] - t.points[tri[0]]);
            EXPECT_GT(a, 0) << "triangles are counter-clockwise";
            sum += a;
        }
        EXPECT_NEAR(sum, area, 1e-9);
    }
}

TEST(StoredGeometry, GeometryModeParsingAndProceduralRequest) {
    EXPECT_EQ(parse_geometry_mode("stored", "--geometry-roads"), GeometryMode::Stored);
    EXPECT_EQ(parse_geometry_mode("procedural", "--geometry-roads"), GeometryMode::Procedural);
    EXPECT_THROW(parse_geometry_mode("triangles", "--geometry-roads"), Error);
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
    const double albedo = 0.5, sky_radiance = 0.2, radius = 8 * 3.14159265358979 / 180, sun = 40;
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

TEST(Sky, DaylightIsBlueAboveBrightNearTheSunAndStarsOnlyShowDirectly) {
    const Sky day = Sky::daylight(TimeOfDay::Day);
    const Color zenith = day.radiance({0, 0, 1});
    EXPECT_GT(zenith.z, zenith.x) << "a clear zenith is blue";
    const Vec3 near_sun = normalize(day.sun_direction() + Vec3{0, 0, 0.05});
    const Vec3 away = normalize(Vec3{-day.sun_direction().x, -day.sun_direction().y, 0.5});
    EXPECT_GT(luminance(day.radiance(near_sun)), 2 * luminance(day.radiance(away))) << "circumsolar brightening";
    EXPECT_TRUE(day.in_sun_disc(day.sun_direction()));
    EXPECT_FALSE(day.in_sun_disc(near_sun));

    const Sky sunset = Sky::daylight(TimeOfDay::Sunset);
    EXPECT_LT(sunset.sun_direction().z, 0.1);
    EXPECT_GT(sunset.sun_radiance().x, 2 * sunset.sun_radiance().z) << "the setting sun is red";

    const Sky night = Sky::daylight(TimeOfDay::Night);
    int stars = 0, samples = 0;
    Rng rng(3);
    for (int i = 0; i < 200000; ++i) {
        const Vec3 dir = normalize(Vec3{rng.next_double() - 0.5, rng.next_double() - 0.5, rng.next_double()});
        if (dir.z <= 0.05) continue;
        ++samples;
        const Color direct = night.radiance(dir, true), indirect = night.radiance(dir, false);
        EXPECT_LT(luminance(indirect), 0.01);
        if (luminance(direct) > 20 * luminance(indirect)) ++stars;
    }
    EXPECT_GT(stars, 0) << "the night sky has stars";
    EXPECT_LT(stars, samples / 100) << "stars are points, not a glow";
}

TEST(WhiteFurnace, FogThatScattersWithoutAbsorbingKeepsItOne) {
    // Ground fog with scattering albedo one: a path only changes direction in it, so under a
    // uniform sky with white surfaces every pixel still sees exactly 1.
    const auto scene = build_render_scene(small_town(), GeometryModes{});
    const MaterialTable materials = all_white_diffuse();
    const Sky sky = Sky::uniform({1, 1, 1});
    RenderSettings r = tiny(8);
    r.integrator.fog.density = 0.03;
    r.integrator.fog.top_z = 40;
    const Film film = render_image({*scene, materials, sky, r.integrator}, view_of_town(r), r);
    for (int c = 0; c < 3; ++c) {
        const ChannelStats s = stats_of(film, c);
        EXPECT_NEAR(s.min, 1.0, 0.01) << "channel " << c;
        EXPECT_NEAR(s.max, 1.0, 0.01) << "channel " << c;
    }
}

TEST(Fog, TransmittanceAndFreeFlightAgree) {
    FogSettings fog;
    fog.density = 0.05;
    fog.top_z = 20;
    const Vec3 origin{0, 0, 2}, up = normalize(Vec3{1, 0, 1});
    // Up through the layer: inside for (20 - 2) * sqrt(2) metres.
    EXPECT_NEAR(fog.length_inside(origin, up, 1e30), 18 * std::sqrt(2.0), 1e-9);
    EXPECT_NEAR(fog.length_inside({0, 0, 30}, normalize(Vec3{1, 0, -1}), 20 * std::sqrt(2.0)), 10 * std::sqrt(2.0),
                1e-9);
    // The share of free flights that get through is the transmittance.
    Rng rng(9);
    int through = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
        double t;
        through += !fog.sample_scatter(origin, up, 1e30, rng.next_double(), &t);
    }
    const double expected = fog.transmittance(origin, up, 1e30);
    EXPECT_NEAR(through / double(n), expected, 4 * std::sqrt(expected * (1 - expected) / n));
    // The phase function integrates to one.
    double integral = 0;
    const int m = 400;
    for (int i = 0; i < m; ++i) {
        const double c = -1 + (i + 0.5) * 2.0 / m;
        integral += hg_phase(fog.g, {0, 0, 1}, {std::sqrt(1 - c * c), 0, c}) * 2 * 3.14159265358979323846 * 2.0 / m;
    }
    EXPECT_NEAR(integral, 1.0, 1e-3);
}
