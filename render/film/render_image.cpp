#include "render/film/render_image.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "common/error.h"
#include "common/progress.h"
#include "render/integrator/pixel_jitter.h"
#include "render/integrator/small_emitters.h"
#include "render/lights/scene_lights.h"
#include "render/materials/bsdf.h"

namespace citygen {

// A pixel's own random stream and the sum of its samples so far: the same numbers whichever
// thread renders it, and whether its samples come in one go or one pass at a time.
struct PixelSamples {
    Rng rng;
    uint64_t jitter_key = 0;  // where in the pixel its samples go (pixel_jitter)
    uint32_t count = 0;       // samples taken so far
    Color sum{0, 0, 0};
    double luminance_squares = 0;  // sum of the samples' squared luminance (for the variance)
    Color direct_sum{0, 0, 0};     // direct_light_at along the sample rays (for --denoise)
    Color gathered_sum{0, 0, 0};   // the small globes' and panes' light the film gathered (small_emitters.h)
};

namespace {

constexpr int kTileSize = 16;

// The albedo the AOV shows and the denoiser divides by: the surface's own colour (a building's
// colour and pattern included), the specular colour for mirrors and glass. Patterns also tilt
// hit.shading_normal (bump), so call this before reading the normal.
Color albedo_at(const PathContext& context, Hit& hit, Vec3 direction) {
    const Material m = surface_material(context.materials, context.building_looks, hit);
    if (m.type == MaterialType::Water) {
        // What the surface reflects of light from everywhere (its directional albedo): mostly the
        // sky and the sun in the Fresnel lobe. The body's dark colour alone would have the
        // denoiser divide the reflection by 0.01 in red and paint it magenta.
        const Vec3 n = dot(hit.shading_normal, direction) < 0 ? hit.shading_normal : -hit.shading_normal;
        const double fresnel = water_reflectance(m, -dot(n, direction));
        return m.specular * fresnel + m.albedo * (1 - fresnel);
    }
    return m.type == MaterialType::Diffuse || m.type == MaterialType::Glossy ? m.albedo : m.specular;
}

// The part of a camera ray's radiance that needs few or no random numbers: what the hit surface
// emits (lamp globes, lit windows) and the aerial haze in front of it, as trace_path adds them on
// its first bounce, and the sun's (or moon's) direct light, with one shadow ray to the centre of
// its disc. The denoiser filters only the rest and adds this back unfiltered, so lamps, lit
// windows and sharp shadows are not smeared. It need not be exact (what it misses is filtered
// with the rest), only free of noise. Zero under --fog, whose first segment may scatter before
// it reaches the surface.
Color direct_light_at(const PathContext& context, const Ray& ray, Hit hit, uint64_t& rays) {
    const IntegratorSettings& settings = context.settings;
    if (settings.fog.density > 0) return {0, 0, 0};
    Color haze{0, 0, 0};
    double transmittance = 1;
    if (settings.haze_extinction > 0) {
        transmittance = aerial_transmittance(settings.haze_extinction, hit.t);
        haze = horizon_haze(context.sky, ray.direction) * (1 - transmittance);
    }
    const Material material = surface_material(context.materials, context.building_looks, hit);
    const Vec3 wo = -ray.direction;
    const bool front = dot(hit.geometric_normal, wo) > 0;
    Color light{0, 0, 0};
    if (front) {  // emitters shine from their front
        light = material.emission;
        // Small globes and panes: gathered by the film, not seen by camera rays (small_emitters.h).
        const bool gathered = context.small_emitters && context.small_emitters->counts_on_film(hit);
        if (context.lights && !context.lights->empty() && !gathered) light = light + context.lights->emitted(hit);
    }
    const Sky& sky = context.sky;
    if (!is_delta(material) && sky.has_sun() && settings.sample_sun) {
        const Vec3 n = front ? hit.geometric_normal : -hit.geometric_normal;
        const Vec3 ns = front ? hit.shading_normal : -hit.shading_normal;
        const Vec3 wi = sky.sun_direction();
        const double cos_i = dot(ns, wi);
        if (cos_i > 0 && dot(n, wi) > 0) {
            ++rays;
            if (!context.scene.occluded(Ray{offset_origin(hit.position, n), wi, 0, 1e30}))
                light = light + bsdf_eval(material, ns, wo, wi) * sky.sun_radiance() * (cos_i * sky.sun_solid_angle());
        }
    }
    return haze + light * transmittance;
}

// The same for a camera ray that hits nothing: the smooth sky (or the haze below the horizon)
// goes back unfiltered too. Were it left to the filter, a pixel that mixes sky and ground (the
// ground plane's far edge, a roof against the sky) would carry the sky's light in what the
// filter mixes with its all-ground neighbours: a dark line along the horizon.
Color direct_light_past_scene(const PathContext& context, const Ray& ray) {
    if (context.settings.fog.density > 0) return {0, 0, 0};
    return smooth_sky_seen(context, ray.direction);
}

// `x`, `y` in the full frame; `i` indexes the film.
void fill_aovs(const PathContext& context, const Camera& camera, int x, int y, size_t i, Film& film) {
    const Ray ray = camera.generate_ray(x + 0.5, y + 0.5);
    Hit hit;
    if (!context.scene.intersect(ray, hit)) return;  // AOVs stay zero for the sky
    const Color albedo = albedo_at(context, hit, ray.direction);
    const Vec3 n = dot(hit.shading_normal, ray.direction) < 0 ? hit.shading_normal : -hit.shading_normal;
    film.depth[i] = static_cast<float>(hit.t);
    for (int c = 0; c < 3; ++c) {
        film.normal[3 * i + c] = static_cast<float>(n[c]);
        film.albedo[3 * i + c] = static_cast<float>(albedo[c]);
    }
    film.object_kind[i] = static_cast<float>(hit.kind);
    film.object_index[i] = static_cast<float>(hit.object);
}

// The denoiser's guides: albedo, normal, depth and direct light averaged over a grid of
// positions inside the pixel, so a window narrower than a pixel still shows (a fixed grid:
// noise-free, and it takes nothing from the pixel's random stream). The direct light goes back
// into the image unfiltered, so its error at a shadow, window or roof edge that crosses the
// pixel is the image's: where it varies over the 6x6 grid by more than kEdgeContrast, the pixel
// takes the 12x12 grid's mean instead (docs/bench/2026-12-water.md, round 5).
void fill_guides(const PathContext& context, const Camera& camera, int x, int y, size_t i, Film& film,
                 uint64_t& rays) {
    constexpr int kGrid = 6, kEdgeGrid = 12;
    constexpr double kEdgeContrast = 0.05;
    double albedo[3], normal[3], direct[3], depth;
    // Sums over an n x n grid; returns whether the direct light's luminance varies over it.
    auto sum_grid = [&](int n) {
        std::fill_n(albedo, 3, 0.0), std::fill_n(normal, 3, 0.0), std::fill_n(direct, 3, 0.0), depth = 0;
        double least = std::numeric_limits<double>::infinity(), most = 0;
        for (int sy = 0; sy < n; ++sy)
            for (int sx = 0; sx < n; ++sx) {
                const Ray ray = camera.generate_ray(x + (sx + 0.5) / n, y + (sy + 0.5) / n);
                Hit hit;
                ++rays;
                Color d;
                if (!context.scene.intersect(ray, hit)) {
                    d = direct_light_past_scene(context, ray);
                } else {
                    const Color a = albedo_at(context, hit, ray.direction);
                    const Vec3 facing =
                        dot(hit.shading_normal, ray.direction) < 0 ? hit.shading_normal : -hit.shading_normal;
                    d = direct_light_at(context, ray, hit, rays);
                    for (int c = 0; c < 3; ++c) albedo[c] += a[c], normal[c] += facing[c];
                    depth += hit.t;
                }
                for (int c = 0; c < 3; ++c) direct[c] += d[c];
                const double l = luminance(d);
                least = std::min(least, l);
                most = std::max(most, l);
            }
        return most - least > kEdgeContrast * most;
    };
    int n = kGrid;
    if (sum_grid(n)) sum_grid(n = kEdgeGrid);
    const double inv = 1.0 / (n * n);
    for (int c = 0; c < 3; ++c) {
        film.guide_albedo[3 * i + c] = static_cast<float>(albedo[c] * inv);
        film.guide_normal[3 * i + c] = static_cast<float>(normal[c] * inv);
        film.guide_direct[3 * i + c] += static_cast<float>(direct[c] * inv);
    }
    film.guide_depth[i] = static_cast<float>(depth * inv);
}

PixelSamples start_pixel(const RenderSettings& settings, int x, int y) {
    const uint64_t key = hash_keys(settings.seed, static_cast<uint64_t>(x), static_cast<uint64_t>(y));
    return {Rng(key), hash_keys(key, 0x6a177e4), 0, Color{0, 0, 0}, 0, Color{0, 0, 0}, Color{0, 0, 0}};
}

// With `direct`, also sums direct_light_at along each sample's ray (it takes no random numbers,
// so the samples stay the same): the denoiser subtracts it, and with it the noise of where in
// the pixel the samples fell (a lamp globe or a sunlit edge covering part of the pixel).
void add_samples(const PathContext& context, const Camera& camera, int x, int y, int count, PixelSamples& pixel,
                 uint64_t& rays, bool direct) {
    // Pair 0 places the sample in the pixel; the first surface's numbers come from pairs 1-4:
    // the light with the window on it, the point on the light, the BSDF's direction, its lobe
    // with the roulettes.
    PairSeeds seeds[5];
    for (uint32_t pair = 0; pair < 5; ++pair) seeds[pair] = pair_seeds(pixel.jitter_key, pair);
    const SmallEmitters::InPixel emitters_here =
        context.small_emitters ? context.small_emitters->in_pixel(x, y) : SmallEmitters::InPixel{};
    for (int s = 0; s < count; ++s) {
        const uint32_t index = pixel.count++;
        const Vec2 j = stratified_pair(seeds[0], index);
        const Ray ray = camera.generate_ray(x + j.x, y + j.y);
        const Vec2 choice = stratified_pair(seeds[1], index), point = stratified_pair(seeds[2], index);
        const Vec2 direction = stratified_pair(seeds[3], index), lobe = stratified_pair(seeds[4], index);
        const FirstVertexNumbers first{
            {choice.x, point.x, point.y, choice.y, lobe.y, direction.x, direction.y, lobe.x}};
        Color L = trace_path(context, ray, pixel.rng, rays, &first);
        const Color gathered = emitters_here.empty() ? Color{0, 0, 0}
                                                     : context.small_emitters->light_in_pixel(
                                                           emitters_here, context, camera, x, y, pixel.jitter_key, index, rays);
        L = L + gathered;
        // A lone non-finite sample would poison the pixel; count it as black.
        if (std::isfinite(L.x) && std::isfinite(L.y) && std::isfinite(L.z)) {
            pixel.sum = pixel.sum + L;
            pixel.gathered_sum = pixel.gathered_sum + gathered;
            pixel.luminance_squares += luminance(L) * luminance(L);
            if (direct) {
                Hit hit;
                ++rays;
                pixel.direct_sum = pixel.direct_sum + (context.scene.intersect(ray, hit)
                                                           ? direct_light_at(context, ray, hit, rays)
                                                           : direct_light_past_scene(context, ray));
            }
        }
    }
}

void store_pixel(const PixelSamples& pixel, int spp, size_t i, Film& film) {
    const double inv = 1.0 / std::max(1, spp);
    for (int c = 0; c < 3; ++c) film.rgb[3 * i + c] = static_cast<float>(pixel.sum[c] * inv);
    if (!film.guide_variance.empty()) {
        // Variance of the pixel's mean luminance: the sample variance over the sample count.
        const double mean = luminance(pixel.sum) * inv;
        const double sample_variance = std::max(0.0, pixel.luminance_squares * inv - mean * mean) * spp / std::max(1, spp - 1);
        film.guide_variance[i] = static_cast<float>(sample_variance * inv);
        // The gathered globes and panes are as good as noise-free: the denoiser leaves them out
        // of what it filters and puts them back (fill_guides adds its grid to guide_direct).
        for (int c = 0; c < 3; ++c) {
            film.guide_sample_direct[3 * i + c] = static_cast<float>((pixel.direct_sum[c] + pixel.gathered_sum[c]) * inv);
            film.guide_direct[3 * i + c] = static_cast<float>(pixel.gathered_sum[c] * inv);
        }
    }
}

// Calls visit(x, y, i) for every pixel of the film, tiles in parallel; `i` indexes the film.
// Tiles not yet started are skipped once `cancel` is set.
template <class Visit>
void for_each_tile(const Film& film, Progress* progress, std::atomic<uint64_t>& total_rays, Visit visit,
                   const std::atomic<bool>* cancel = nullptr) {
    const int tiles_x = (film.width + kTileSize - 1) / kTileSize;
    const int tiles_y = (film.height + kTileSize - 1) / kTileSize;
    tbb::parallel_for(tbb::blocked_range<int>(0, tiles_x * tiles_y, 1), [&](const tbb::blocked_range<int>& range) {
        for (int tile = range.begin(); tile != range.end(); ++tile) {
            if (cancel && cancel->load(std::memory_order_relaxed)) continue;
            uint64_t rays = 0;
            const int fx0 = (tile % tiles_x) * kTileSize, fy0 = (tile / tiles_x) * kTileSize;
            for (int fy = fy0; fy < std::min(fy0 + kTileSize, film.height); ++fy)
                for (int fx = fx0; fx < std::min(fx0 + kTileSize, film.width); ++fx)
                    visit(film.x0 + fx, film.y0 + fy, static_cast<size_t>(fy) * film.width + fx, rays);
            total_rays += rays;
            if (progress) progress->advance();
        }
    });
}

}  // namespace

PixelRegion render_region(const RenderSettings& settings) {
    const PixelRegion& r = settings.region;
    if (r.empty() && r.x0 == 0 && r.y0 == 0 && r.x1 == 0 && r.y1 == 0) return {0, 0, settings.width, settings.height};
    if (r.x0 < 0 || r.y0 < 0 || r.x1 > settings.width || r.y1 > settings.height || r.empty())
        throw Error("--region " + std::to_string(r.x0) + "," + std::to_string(r.y0) + "," + std::to_string(r.x1) + "," +
                    std::to_string(r.y1) + ": must be a non-empty rectangle inside the " +
                    std::to_string(settings.width) + "x" + std::to_string(settings.height) + " frame");
    return r;
}

namespace {

// An empty film for the region, with the guide and AOV buffers the settings ask for.
Film make_film(const PixelRegion& region, const RenderSettings& settings) {
    Film film;
    film.width = region.width();
    film.height = region.height();
    film.x0 = region.x0;
    film.y0 = region.y0;
    const size_t pixels = static_cast<size_t>(film.width) * film.height;
    film.rgb.assign(3 * pixels, 0.f);
    if (settings.denoise_guides) {
        film.guide_variance.assign(pixels, 0.f);
        film.guide_sample_direct.assign(3 * pixels, 0.f);
        film.guide_direct.assign(3 * pixels, 0.f);
    }
    if (settings.aovs) {
        film.depth.assign(pixels, 0.f);
        film.normal.assign(3 * pixels, 0.f);
        film.albedo.assign(3 * pixels, 0.f);
        film.object_kind.assign(pixels, 0.f);
        film.object_index.assign(pixels, 0.f);
    }
    return film;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Passes of one sample per pixel until the time limit (or settings.spp). Returns the film and
// sets `spp` to the samples per pixel taken.
Film render_time_limited(const PathContext& context, const Camera& camera, const RenderSettings& settings,
                         std::chrono::steady_clock::time_point start, std::atomic<uint64_t>& total_rays, int& spp) {
    ProgressiveRender passes(context, camera, settings);
    const uint64_t limit_ms = static_cast<uint64_t>(settings.time_limit_seconds * 1000);
    Progress progress("render (time limit)", limit_ms, settings.quiet);
    uint64_t shown_ms = 0;
    double last_pass = 0;
    while (passes.spp() < settings.spp &&
           (passes.spp() == 0 || seconds_since(start) + last_pass <= settings.time_limit_seconds)) {
        const double pass_start = seconds_since(start);
        total_rays += passes.add_pass();
        last_pass = seconds_since(start) - pass_start;
        const uint64_t now_ms = std::min(limit_ms, static_cast<uint64_t>(seconds_since(start) * 1000));
        if (now_ms > shown_ms) progress.advance(now_ms - shown_ms), shown_ms = now_ms;
    }
    progress.finish();
    spp = passes.spp();
    return passes.film();
}

}  // namespace

Film render_image(const PathContext& scene_context, const Camera& camera, const RenderSettings& settings,
                  RenderStats* stats) {
    PathContext context = scene_context;
    SmallEmitters small_emitters;
    if (context.lights && !context.lights->empty()) {
        small_emitters = SmallEmitters(*context.lights, camera, settings.gather_panes);
        context.small_emitters = &small_emitters;
    }
    Film film = make_film(render_region(settings), settings);
    const size_t pixels = static_cast<size_t>(film.width) * film.height;
    const int tile_count = ((film.width + kTileSize - 1) / kTileSize) * ((film.height + kTileSize - 1) / kTileSize);
    std::atomic<uint64_t> total_rays{0};
    const auto start = std::chrono::steady_clock::now();
    int spp = settings.spp;
    if (settings.time_limit_seconds <= 0) {
        Progress progress("render", static_cast<uint64_t>(tile_count), settings.quiet);
        for_each_tile(film, &progress, total_rays, [&](int x, int y, size_t i, uint64_t& rays) {
            PixelSamples pixel = start_pixel(settings, x, y);
            add_samples(context, camera, x, y, settings.spp, pixel, rays, settings.denoise_guides);
            store_pixel(pixel, settings.spp, i, film);
        });
        progress.finish();
    } else {
        film = render_time_limited(scene_context, camera, settings, start, total_rays, spp);
    }
    if (settings.aovs) {
        for_each_tile(film, nullptr, total_rays, [&](int x, int y, size_t i, uint64_t& rays) {
            fill_aovs(context, camera, x, y, i, film);
            ++rays;
        });
    }
    if (settings.denoise_guides) {
        film.guide_albedo.assign(3 * pixels, 0.f);
        film.guide_normal.assign(3 * pixels, 0.f);
        film.guide_depth.assign(pixels, 0.f);
        for_each_tile(film, nullptr, total_rays, [&](int x, int y, size_t i, uint64_t& rays) {
            fill_guides(context, camera, x, y, i, film, rays);
        });
    }
    if (stats) {
        stats->seconds = seconds_since(start);
        stats->rays = total_rays.load();
        stats->spp = spp;
    }
    return film;
}

ProgressiveRender::ProgressiveRender(const PathContext& context, const Camera& camera, const RenderSettings& settings)
    : context_(context), camera_(camera), settings_(settings), film_(make_film(render_region(settings), settings)) {
    if (context_.lights && !context_.lights->empty()) {
        small_emitters_ = std::make_unique<SmallEmitters>(*context_.lights, camera, settings.gather_panes);
        context_.small_emitters = small_emitters_.get();
    }
    pixels_.reserve(static_cast<size_t>(film_.width) * film_.height);
    for (int fy = 0; fy < film_.height; ++fy)
        for (int fx = 0; fx < film_.width; ++fx) pixels_.push_back(start_pixel(settings, film_.x0 + fx, film_.y0 + fy));
}

ProgressiveRender::~ProgressiveRender() = default;

uint64_t ProgressiveRender::add_pass(const std::atomic<bool>* cancel) {
    std::atomic<uint64_t> rays{0};
    for_each_tile(
        film_, nullptr, rays,
        [&](int x, int y, size_t i, uint64_t& pixel_rays) {
            add_samples(context_, camera_, x, y, 1, pixels_[i], pixel_rays, settings_.denoise_guides);
        },
        cancel);
    ++spp_;
    return rays.load();
}

Film ProgressiveRender::film() const {
    Film film = film_;
    for (size_t i = 0; i < pixels_.size(); ++i) store_pixel(pixels_[i], spp_, i, film);
    return film;
}

}  // namespace citygen
