// The image loop: the same seed gives the same pixels whatever the thread count, and the
// denoiser's guides are the pixels' means.
#include <cmath>
#include <cstring>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "render/film/render_image.h"
#include "render/geometry/build_render_scene.h"
#include "render/lights/scene_lights.h"
#include "render/materials/bsdf.h"
#include "tests/render/small_town.h"

using namespace citygen;
using namespace citygen::test;

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

// The viewer's still frames: n passes of ProgressiveRender are the n-spp image, byte for byte,
// at night too (lamps, small globes gathered by the film).
TEST(ProgressiveRender, PassesAddUpToTheFixedSppImage) {
    Scene town = small_town();
    Lamp lamp;
    lamp.position = {0, -30, 0};
    town.lamps.push_back(lamp);
    const auto scene = build_render_scene(town, GeometryModes{});
    const MaterialTable materials = default_materials();
    const Sky sky = Sky::daylight(TimeOfDay::Night);
    const SceneLights lights(town, FacadeOptions{}, LightOptions{});
    RenderSettings r = tiny(3);
    r.width = 40;
    r.height = 36;
    const PathContext context{*scene, materials, sky, r.integrator, nullptr, &lights};
    const Camera camera = view_of_town(r);
    ProgressiveRender passes(context, camera, r);
    EXPECT_EQ(0, passes.spp());
    uint64_t rays = 0;
    for (int pass = 0; pass < 3; ++pass) rays += passes.add_pass();
    EXPECT_EQ(3, passes.spp());
    EXPECT_GT(rays, 40u * 36u * 3u);
    const Film progressive = passes.film();
    const Film fixed = render_image(context, camera, r);
    ASSERT_EQ(fixed.rgb.size(), progressive.rgb.size());
    EXPECT_EQ(0, std::memcmp(fixed.rgb.data(), progressive.rgb.data(), fixed.rgb.size() * sizeof(float)));
    r.spp = 2;  // and not any other spp's
    const Film two = render_image(context, camera, r);
    EXPECT_NE(0, std::memcmp(two.rgb.data(), progressive.rgb.data(), two.rgb.size() * sizeof(float)));
}

// The denoiser's direct-light guide goes back into the image unfiltered, so it must be each
// pixel's mean: on the sunlit town, where roof and shadow edges cross pixels, it agrees with the
// mean along many random sample rays (guide_sample_direct, which converges to the same).
TEST(DenoiseGuides, TheDirectLightIsThePixelsMean) {
    const auto scene = build_render_scene(small_town(), GeometryModes{});
    const MaterialTable materials = default_materials();
    const Sky sky = Sky::daylight(TimeOfDay::Day);
    RenderSettings r = tiny(1024);
    r.integrator = IntegratorSettings{};
    r.integrator.max_depth = 0;
    r.denoise_guides = true;
    const PathContext context{*scene, materials, sky, r.integrator};
    const Film film = render_image(context, view_of_town(r), r);
    double error = 0, light = 0;
    for (size_t i = 0; i < film.guide_direct.size(); i += 3) {
        const double grid = luminance({film.guide_direct[i], film.guide_direct[i + 1], film.guide_direct[i + 2]});
        const double samples =
            luminance({film.guide_sample_direct[i], film.guide_sample_direct[i + 1], film.guide_sample_direct[i + 2]});
        error += std::abs(grid - samples);
        light += samples;
    }
    // The 6x6 grid alone is 0.59% off, the 12x12 where the light varies 0.31%; 1024 samples'
    // own noise is about 0.2%.
    EXPECT_LT(error / light, 0.0045);
}
