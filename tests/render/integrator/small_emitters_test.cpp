// Lamp globes and lit panes a few pixels wide (render/integrator/small_emitters.h): the light each
// pixel gathers from them with its extra rays is what camera rays through the pixel would have
// seen of them, so the picture's mean stays and only the noise goes.
#include <cmath>
#include <cstring>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "render/camera/camera.h"
#include "render/film/denoise.h"
#include "render/film/render_image.h"
#include "render/geometry/build_render_scene.h"
#include "render/geometry/lamp_shape.h"
#include "render/integrator/small_emitters.h"
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

Ring rectangle(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

// Blocks of flats with lit windows, seen from far above: their panes are a fraction of a pixel,
// and the southern blocks hide part of the northern ones' facades.
Scene flats_from_above() {
    Scene s;
    s.header.seed = 11;
    s.header.bounds_min = {-80, -80};
    s.header.bounds_max = {80, 80};
    s.ground.min = s.header.bounds_min;
    s.ground.max = s.header.bounds_max;
    Building north, south, west;
    north.outer = rectangle(-40, 10, 40, 22);
    north.height = 24;
    south.outer = rectangle(-40, -22, 40, -10);
    south.height = 15;
    west.outer = rectangle(-70, -30, -55, 30);
    west.height = 30;
    s.buildings = {north, south, west};
    return s;
}

constexpr int kWidth = 64, kHeight = 40;
Camera above_the_flats(int width = kWidth, int height = kHeight) {
    return Camera::look_at({-260, -240, 160}, {-10, 0, 8}, 22, width, height);
}

double luminance_of(Color c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

LightOptions lamps_alone() {
    LightOptions options;
    options.lit_windows = 0;
    return options;
}

LightOptions windows_alone() {
    LightOptions options;
    options.lamps = false;
    options.lit_windows = 0.5;
    return options;
}

// For every pixel: what a kGrid x kGrid grid of camera rays through it sees of the emitters the
// film gathers, against the mean of kSamples samples of the light it gathers. Returns the number
// of pixels that see some.
template <int kGrid = 32, int kSamples = 64>
int expect_gathered_light_is_what_camera_rays_see(const Scene& scene, const SceneLights& lights,
                                                  const Camera& camera, const SmallEmitters& emitters) {
    const MaterialTable materials = default_materials();
    const Sky sky = Sky::daylight(TimeOfDay::Night);
    int pixels_seen = 0;
    for (GeometryMode mode : {GeometryMode::Stored, GeometryMode::Procedural}) {
        const auto render_scene = build_render_scene(scene, GeometryModes::all(mode), FacadeOptions{scene.header.seed});
        IntegratorSettings settings;
        const PathContext context{*render_scene, materials, sky, settings, nullptr, &lights};
        double seen_total = 0, gathered_total = 0;
        int pixels = 0;
        uint64_t rays = 0;
        for (int y = 0; y < camera.height(); ++y) {
            for (int x = 0; x < camera.width(); ++x) {
                double seen = 0;
                for (int gy = 0; gy < kGrid; ++gy) {
                    for (int gx = 0; gx < kGrid; ++gx) {
                        const Ray ray = camera.generate_ray(x + (gx + 0.5) / kGrid, y + (gy + 0.5) / kGrid);
                        Hit hit;
                        if (render_scene->intersect(ray, hit) && emitters.counts_on_film(hit) &&
                            dot(hit.geometric_normal, ray.direction) < 0)
                            seen += luminance_of(lights.emitted(hit));
                    }
                }
                seen /= kGrid * kGrid;
                double gathered = 0;
                for (uint32_t i = 0; i < kSamples; ++i)
                    gathered += luminance_of(emitters.light_in_pixel(emitters.in_pixel(x, y), context, camera, x, y,
                                                                     1000 + x * 31 + y, i, rays));
                gathered /= kSamples;
                // An emitter seen in a pixel its rectangle misses would be lost.
                if (seen > 0) {
                    ++pixels;
                    EXPECT_GT(gathered, 0) << "an emitter is seen in pixel " << x << "," << y << " but not gathered there";
                }
                seen_total += seen;
                gathered_total += gathered;
            }
        }
        EXPECT_NEAR(gathered_total, seen_total, 0.02 * seen_total) << (mode == GeometryMode::Stored ? "stored" : "procedural");
        pixels_seen = pixels;
    }
    return pixels_seen;
}

}  // namespace

TEST(SmallGlobes, PixelLightIsWhatCameraRaysSeeOfTheGlobes) {
    const Scene scene = lamps_down_a_road();
    const SceneLights lights(scene, FacadeOptions{scene.header.seed}, lamps_alone());
    const Camera camera = Camera::look_at({-4, 0, 5}, {100, 0, 5}, 30, kWidth, kWidth * 40 / 64);
    const SmallEmitters globes(lights, camera);
    ASSERT_GT(globes.size(), 20u);  // most globes are small from here ...
    ASSERT_LT(globes.size(), 56u);  // ... the nearest are not
    // Stored globes are facets a little outside the sphere: both modes.
    EXPECT_GT(expect_gathered_light_is_what_camera_rays_see(scene, lights, camera, globes), 20);
}

TEST(SmallPanes, PixelLightIsWhatCameraRaysSeeOfThePanes) {
    const Scene scene = flats_from_above();
    const SceneLights lights(scene, FacadeOptions{scene.header.seed}, windows_alone());
    const Camera camera = above_the_flats();
    const SmallEmitters panes(lights, camera);
    ASSERT_GT(panes.pane_count(), 100u);
    EXPECT_EQ(panes.size(), panes.pane_count());
    // Close up to a facade, its panes are many pixels wide: the camera rays find them.
    const Camera close = Camera::look_at({0, -30, 8}, {0, -22, 8}, 20, kWidth, kHeight);
    EXPECT_EQ(0u, SmallEmitters(lights, close).pane_count());
    EXPECT_EQ(0u, SmallEmitters(lights, camera, false).size());
    EXPECT_GT(expect_gathered_light_is_what_camera_rays_see(scene, lights, camera, panes), 100);
}

// From farther (a small image of the same flats) a pixel holds more panes than a sample aims
// rays at: it picks some in proportion to the area they cover, and the light stays the same.
TEST(SmallPanes, APixelOfManyPanesAimsAFewRaysAndKeepsTheirLight) {
    const Scene scene = flats_from_above();
    const SceneLights lights(scene, FacadeOptions{scene.header.seed}, windows_alone());
    const Camera camera = above_the_flats(12, 8);
    const SmallEmitters panes(lights, camera);
    const auto render_scene = build_render_scene(scene, GeometryModes{}, FacadeOptions{scene.header.seed});
    const MaterialTable materials = default_materials();
    const Sky sky = Sky::daylight(TimeOfDay::Night);
    IntegratorSettings settings;
    const PathContext context{*render_scene, materials, sky, settings, nullptr, &lights};
    size_t crowded = 0, most = 0;
    for (int y = 0; y < camera.height(); ++y) {
        for (int x = 0; x < camera.width(); ++x) {
            const SmallEmitters::InPixel here = panes.in_pixel(x, y);
            most = std::max(most, here.last - here.first);
            if (here.last - here.first <= SmallEmitters::kMaxRaysPerSample) continue;
            ++crowded;
            uint64_t rays = 0;
            panes.light_in_pixel(here, context, camera, x, y, 77, 0, rays);
            EXPECT_EQ(rays, uint64_t{SmallEmitters::kMaxRaysPerSample});
        }
    }
    ASSERT_GT(crowded, 3u) << "the most panes in a pixel: " << most;
    EXPECT_GT((expect_gathered_light_is_what_camera_rays_see<128, 1024>(scene, lights, camera, panes)), 10);
}

namespace {

struct Renders {
    Film gathered[2], direct[2];  // two seeds each
};

Renders render_flats(int spp) {
    const Scene scene = flats_from_above();
    const auto render_scene = build_render_scene(scene, GeometryModes{}, FacadeOptions{scene.header.seed});
    const MaterialTable materials = default_materials();
    const Sky sky = Sky::daylight(TimeOfDay::Night);
    const SceneLights lights(scene, FacadeOptions{scene.header.seed}, windows_alone());
    RenderSettings r;
    r.width = kWidth;
    r.height = kHeight;
    r.spp = spp;
    r.quiet = true;
    r.integrator.max_depth = 1;
    const PathContext context{*render_scene, materials, sky, r.integrator, nullptr, &lights};
    Renders out;
    for (int seed = 0; seed < 2; ++seed) {
        r.seed = 1 + seed;
        r.gather_panes = true;
        out.gathered[seed] = render_image(context, above_the_flats(), r);
        r.gather_panes = false;
        out.direct[seed] = render_image(context, above_the_flats(), r);
    }
    return out;
}

double pixel_luminance(const Film& film, size_t i) {
    return 0.2126 * film.rgb[3 * i] + 0.7152 * film.rgb[3 * i + 1] + 0.0722 * film.rgb[3 * i + 2];
}

// Sum over pixels of (a - b)^2 / 2: twice the pixels' variance when a and b are two seeds.
double seed_variance(const Film& a, const Film& b) {
    double sum = 0;
    for (size_t i = 0; i < a.rgb.size() / 3; ++i) sum += 0.5 * std::pow(pixel_luminance(a, i) - pixel_luminance(b, i), 2);
    return sum;
}

}  // namespace

TEST(SmallPanes, GatheringKeepsTheMeanAndLowersTheNoise) {
    const Renders r = render_flats(64);
    // The same mean image: per pixel, the difference of the two estimators against its noise.
    double sum = 0, sum2 = 0, mean = 0;
    const size_t n = r.gathered[0].rgb.size() / 3;
    for (int seed = 0; seed < 2; ++seed) {
        for (size_t i = 0; i < n; ++i) {
            const double d = pixel_luminance(r.gathered[seed], i) - pixel_luminance(r.direct[seed], i);
            sum += d;
            sum2 += d * d;
            mean += pixel_luminance(r.direct[seed], i);
        }
    }
    const double count = 2.0 * n, difference = sum / count;
    const double standard_error = std::sqrt((sum2 / count - difference * difference) / count);
    EXPECT_LT(std::fabs(difference), 4 * standard_error + 1e-4 * mean / count) << "mean " << mean / count;
    EXPECT_GT(mean / count, 0);
    // The panes' pixel coverage was most of the noise from up here.
    const double gathered = seed_variance(r.gathered[0], r.gathered[1]);
    const double direct = seed_variance(r.direct[0], r.direct[1]);
    EXPECT_LT(gathered, 0.5 * direct) << gathered << " against " << direct;
}

TEST(SmallPanes, SameImageWhateverTheThreadsAndTiles) {
    const Scene scene = flats_from_above();
    const auto render_scene = build_render_scene(scene, GeometryModes{}, FacadeOptions{scene.header.seed});
    const MaterialTable materials = default_materials();
    const Sky sky = Sky::daylight(TimeOfDay::Night);
    const SceneLights lights(scene, FacadeOptions{scene.header.seed}, windows_alone());
    RenderSettings r;
    r.width = kWidth;
    r.height = kHeight;
    r.spp = 4;
    r.quiet = true;
    const PathContext context{*render_scene, materials, sky, r.integrator, nullptr, &lights};
    const Camera camera = above_the_flats();
    Film one, two;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = render_image(context, camera, r);
    }
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
        two = render_image(context, camera, r);
    }
    ASSERT_EQ(one.rgb.size(), two.rgb.size());
    EXPECT_EQ(0, std::memcmp(one.rgb.data(), two.rgb.data(), one.rgb.size() * sizeof(float)));
    r.region = {17, 5, 50, 31};
    const Film tile = render_image(context, camera, r);
    for (int y = r.region.y0; y < r.region.y1; ++y)
        for (int x = r.region.x0; x < r.region.x1; ++x)
            for (int c = 0; c < 3; ++c)
                ASSERT_EQ(one.rgb[3 * (y * kWidth + x) + c],
                          tile.rgb[3 * ((y - r.region.y0) * tile.width + x - r.region.x0) + c]);
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
