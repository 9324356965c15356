// Lamp globes a few pixels wide (render/integrator/small_globes.h): the light each pixel gathers from them
// with its extra rays is what camera rays through the pixel would have seen of them.
#include <gtest/gtest.h>

#include "render/camera/camera.h"
#include "render/film/denoise.h"
#include "render/film/render_image.h"
#include "render/geometry/build_render_scene.h"
#include "render/geometry/lamp_shape.h"
#include "render/integrator/small_globes.h"
#include "render/lights/scene_lights.h"

using namespace citygen;

namespace {

// Lamps along a road running away from the camera, and a block that hides some of them.
Scene lamps_down_a_road() {
    Scene s;
    s.header.seed = 3;
    s.header.bounds_min = {-20, -10};
    s.header.bounds_max = {200, 10};
    s.ground.min = s.header.bounds_min;
    s.ground.max = s.header.bounds_max;
    Building block;
    block.outer = {{60, 2}, {80, 2}, {80, 9}, {60, 9}};
    block.height = 6;
    s.buildings = {block};
    for (int i = 0; i < 30; ++i) {
        for (double y : {-5.0, 5.5}) {
            Lamp lamp;
            lamp.position = {6.0 * i, y, 0};
            lamp.height = 5 + (i % 3);
            s.lamps.push_back(lamp);
        }
    }
    return s;
}

double luminance_of(Color c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

LightOptions lamps_alone() {
    LightOptions options;
    options.lit_windows = 0;
    return options;
}

}  // namespace

TEST(SmallGlobes, PixelLightIsWhatCameraRaysSeeOfTheGlobes) {
    const Scene scene = lamps_down_a_road();
    const MaterialTable materials = default_materials();
    const Sky sky = Sky::daylight(TimeOfDay::Night);
    const SceneLights lights(scene, FacadeOptions{scene.header.seed}, lamps_alone());
    constexpr int kWidth = 64, kHeight = 40, kGrid = 32, kSamples = 64;
    const Camera camera = Camera::look_at({-4, 0, 5}, {100, 0, 5}, 30, kWidth, kHeight);
    const SmallGlobes globes(lights, camera);
    ASSERT_GT(globes.size(), 20u);  // most globes are small from here ...
    ASSERT_LT(globes.size(), 56u);  // ... the nearest are not

    // Stored globes are facets a little outside the sphere: both modes.
    for (GeometryMode mode : {GeometryMode::Stored, GeometryMode::Procedural}) {
        const auto render_scene = build_render_scene(scene, GeometryModes::all(mode), FacadeOptions{scene.header.seed});
        IntegratorSettings settings;
        const PathContext context{*render_scene, materials, sky, settings, nullptr, &lights};
        double seen_total = 0, gathered_total = 0;
        int pixels_with_globes = 0;
        uint64_t rays = 0;
        for (int y = 0; y < kHeight; ++y) {
            for (int x = 0; x < kWidth; ++x) {
                // What a fine grid of camera rays through the pixel sees of the small globes.
                double seen = 0;
                for (int gy = 0; gy < kGrid; ++gy) {
                    for (int gx = 0; gx < kGrid; ++gx) {
                        const Ray ray = camera.generate_ray(x + (gx + 0.5) / kGrid, y + (gy + 0.5) / kGrid);
                        Hit hit;
                        if (render_scene->intersect(ray, hit) && globes.counts_on_film(hit) &&
                            dot(hit.geometric_normal, ray.direction) < 0)
                            seen += luminance_of(lights.emitted(hit));
                    }
                }
                seen /= kGrid * kGrid;
                double gathered = 0;
                for (uint32_t i = 0; i < kSamples; ++i)
                    gathered += luminance_of(
                        globes.light_in_pixel(globes.in_pixel(x, y), context, camera, x, y, 1000 + x * 31 + y, i, rays));
                gathered /= kSamples;
                // A globe seen in a pixel its rectangle misses would be lost.
                if (seen > 0) {
                    ++pixels_with_globes;
                    EXPECT_GT(gathered, 0) << "a globe is seen in pixel " << x << "," << y << " but not gathered there";
                }
                seen_total += seen;
                gathered_total += gathered;
            }
        }
        EXPECT_GT(pixels_with_globes, 20);
        EXPECT_NEAR(gathered_total, seen_total, 0.02 * seen_total) << (mode == GeometryMode::Stored ? "stored" : "procedural");
    }
}

TEST(SmallGlobes, DenoisingKeepsTheirLightWhereItIs) {
    // The gathered light is nearly noise-free: the denoiser must put it back unfiltered, not
    // spread it over the road around the globe.
    const Scene scene = lamps_down_a_road();
    const auto render_scene = build_render_scene(scene, GeometryModes::all(GeometryMode::Procedural), FacadeOptions{scene.header.seed});
    const MaterialTable materials = default_materials();
    const Sky sky = Sky::daylight(TimeOfDay::Night);
    const SceneLights lights(scene, FacadeOptions{scene.header.seed}, lamps_alone());
    RenderSettings settings;
    settings.width = 64;
    settings.height = 40;
    settings.spp = 16;
    settings.quiet = true;
    settings.aovs = true;
    settings.denoise_guides = true;
    const Camera camera = Camera::look_at({-4, 0, 5}, {100, 0, 5}, 30, settings.width, settings.height);
    Film film = render_image({*render_scene, materials, sky, settings.integrator, nullptr, &lights}, camera, settings);
    double mean = 0;
    for (float v : film.rgb) mean += v;
    mean /= film.rgb.size();
    denoise(film, 0.2 / mean, DenoiseSettings{});
    // The bright pixels, the distant globes', keep their light.
    double raw = 0, filtered = 0;
    int globe_pixels = 0;
    for (size_t i = 0; i < film.rgb.size() / 3; ++i) {
        const double r = luminance_of({film.raw_rgb[3 * i], film.raw_rgb[3 * i + 1], film.raw_rgb[3 * i + 2]});
        if (!(r > 5 * mean)) continue;
        ++globe_pixels;
        raw += r;
        filtered += luminance_of({film.rgb[3 * i], film.rgb[3 * i + 1], film.rgb[3 * i + 2]});
    }
    EXPECT_GT(globe_pixels, 10);
    EXPECT_NEAR(filtered, raw, 0.01 * raw);  // 2.4% of it went astray when the filter had it
}
