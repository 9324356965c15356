// Lamps, lit windows and many-light sampling (render/lights/): the light sampler's
// probabilities, and unbiased next-event estimation whichever sampler picks the light.
#include <algorithm>
#include <cmath>
#include <memory>

#include <gtest/gtest.h>

#include "build_render_scene.h"
#include "light_sampler.h"
#include "render_image.h"
#include "rng.h"
#include "scene_lights.h"

using namespace citygen;

namespace {

Ring rectangle(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

// A street between two blocks of flats, 48 lamps along it and around, lit windows on the facades.
Scene lamp_street() {
    Scene s;
    s.header.seed = 7;
    s.header.bounds_min = {-60, -60};
    s.header.bounds_max = {60, 60};
    s.ground.min = {-60, -60};
    s.ground.max = {60, 60};
    Building north, south;
    north.outer = rectangle(-40, 8, 40, 20);
    north.height = 15;
    south.outer = rectangle(-40, -20, 40, -8);
    south.height = 12;
    s.buildings = {north, south};
    RoadEdge road;
    road.quad = rectangle(-60, -4, 60, 4);
    s.roads.push_back(road);
    for (int i = 0; i < 24; ++i) {
        for (double y : {-6.0, 6.0}) {
            Lamp lamp;
            lamp.position = {-55 + 4.8 * i, y + (i % 3) * 0.3, 0};
            lamp.height = 4 + (i % 4);
            s.lamps.push_back(lamp);
        }
    }
    return s;
}

LightOptions night_lights(LightSamplerKind kind) {
    LightOptions o;
    o.sampler = kind;
    o.lit_windows = 0.4;
    return o;
}

double pixel_luminance(const Film& film, size_t i) {
    return 0.2126 * film.rgb[3 * i] + 0.7152 * film.rgb[3 * i + 1] + 0.0722 * film.rgb[3 * i + 2];
}

struct Difference {
    double mean = 0, reference_mean = 0, standard_error = 0;
};

// Mean of (film - reference) per pixel and its standard error: the picture's content cancels,
// what is left is the two estimators' noise (pixels are independent) and any bias.
Difference difference(const Film& film, const Film& reference) {
    const size_t n = film.rgb.size() / 3;
    double sum = 0, sum2 = 0, ref = 0;
    for (size_t i = 0; i < n; ++i) {
        const double d = pixel_luminance(film, i) - pixel_luminance(reference, i);
        sum += d;
        sum2 += d * d;
        ref += pixel_luminance(reference, i);
    }
    Difference r;
    r.mean = sum / n;
    r.reference_mean = ref / n;
    r.standard_error = std::sqrt(std::max(0.0, sum2 / n - r.mean * r.mean) / n);
    return r;
}

}  // namespace

TEST(LightSampler, ProbabilitiesSumToOneAndMatchWhatSamplingReports) {
    const Scene scene = lamp_street();
    for (LightSamplerKind kind : {LightSamplerKind::Tree, LightSamplerKind::Power, LightSamplerKind::Uniform}) {
        const SceneLights lights(scene, FacadeOptions{scene.header.seed}, night_lights(kind));
        ASSERT_EQ(lights.lamp_count(), scene.lamps.size());
        ASSERT_GT(lights.strip_count(), 0u) << "lit windows should be lights";
        const LightSampler& sampler = lights.sampler();
        Rng rng(11);
        for (int trial = 0; trial < 200; ++trial) {
            // Points on the road, on facades and in the air; normals up, sideways or none.
            const Vec3 p{-58 + 116 * rng.next_double(), -7 + 14 * rng.next_double(), 12 * rng.next_double()};
            const Vec3 normals[3] = {{0, 0, 1}, {0, trial % 2 ? 1.0 : -1.0, 0}, {0, 0, 0}};
            const Vec3 n = normals[trial % 3];
            double total = 0;
            for (uint32_t i = 0; i < sampler.size(); ++i) total += sampler.pmf(p, n, i);
            EXPECT_NEAR(total, 1.0, 1e-9) << to_string(kind) << " at trial " << trial;
            for (int k = 0; k < 5; ++k) {
                uint32_t light;
                double pmf;
                if (!sampler.sample(p, n, rng.next_double(), &light, &pmf)) continue;
                EXPECT_NEAR(pmf, sampler.pmf(p, n, light), 1e-12 * std::max(1.0, pmf)) << to_string(kind);
                EXPECT_GT(pmf, 0);
            }
        }
    }
}

TEST(SceneLights, PdfOfAnEmitterHitEqualsThePdfItWasSampledWith) {
    // Procedural mode: the globes are exact spheres, so the hit is the sampled point.
    const Scene scene = lamp_street();
    const auto render_scene = build_render_scene(scene, GeometryModes::all(GeometryMode::Procedural), FacadeOptions{scene.header.seed});
    const SceneLights lights(scene, FacadeOptions{scene.header.seed}, night_lights(LightSamplerKind::Tree));
    Rng rng(5);
    int lamps = 0, windows = 0;
    for (int trial = 0; trial < 4000; ++trial) {
        const Vec3 p{-50 + 100 * rng.next_double(), -3.5 + 7 * rng.next_double(), 0.03};
        const Vec3 n{0, 0, 1};
        const double u[4] = {rng.next_double(), rng.next_double(), rng.next_double(), rng.next_double()};
        LightSample ls;
        if (!lights.sample(p, n, u, &ls)) continue;
        Hit hit;
        if (!render_scene->intersect(Ray{p, ls.direction, 1e-4, 1e30}, hit)) continue;
        if (std::fabs(hit.t - ls.distance) > 1e-4 * ls.distance + 1e-4) continue;  // occluded
        const Color emitted = lights.emitted(hit);
        ASSERT_GT(emitted.x + emitted.y + emitted.z, 0) << "the sampled point emits";
        EXPECT_NEAR(lights.pdf(p, n, hit), ls.pdf, 1e-6 * ls.pdf);
        (hit.kind == ObjectKind::Lamp ? lamps : windows)++;
    }
    EXPECT_GT(lamps, 100);
    EXPECT_GT(windows, 20);
}

TEST(SceneLights, EverySamplerAndBsdfSamplingAloneConvergeToTheSameMean) {
    const Scene scene = lamp_street();
    const auto render_scene = build_render_scene(scene, GeometryModes::all(GeometryMode::Procedural), FacadeOptions{scene.header.seed});
    const MaterialTable materials = default_materials();
    const Sky sky = Sky::daylight(TimeOfDay::Night);
    RenderSettings r;
    r.width = 24;
    r.height = 16;
    r.quiet = true;
    r.integrator.max_depth = 3;
    const Camera camera = Camera::look_at({-30, 0, 1.7}, {10, 0, 4}, 70, r.width, r.height);

    auto render_with = [&](LightSamplerKind kind, bool next_event, int spp) {
        const SceneLights lights(scene, FacadeOptions{scene.header.seed}, night_lights(kind));
        RenderSettings settings = r;
        settings.spp = spp;
        settings.integrator.sample_lights = next_event;
        return render_image({*render_scene, materials, sky, settings.integrator, &lights}, camera, settings);
    };
    const Film reference = render_with(LightSamplerKind::Tree, true, 256);
    const Film cases[] = {render_with(LightSamplerKind::Power, true, 256),
                          render_with(LightSamplerKind::Uniform, true, 256),
                          render_with(LightSamplerKind::Tree, false, 1024)};
    const char* names[] = {"power", "uniform", "BSDF sampling alone"};
    for (int i = 0; i < 3; ++i) {
        const Difference d = difference(cases[i], reference);
        EXPECT_LT(std::fabs(d.mean), 4 * d.standard_error)
            << names[i] << " differs from the tree by " << d.mean << " +- " << d.standard_error << " (mean "
            << d.reference_mean << ")";
        EXPECT_LT(d.standard_error, 0.05 * d.reference_mean) << names[i] << ": too noisy to tell";
    }
}
