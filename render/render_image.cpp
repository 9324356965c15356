#include "render_image.h"

#include <algorithm>
#include <atomic>
#include <chrono>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "progress.h"

namespace citygen {

namespace {

constexpr int kTileSize = 16;

void fill_aovs(const PathContext& context, const Camera& camera, int x, int y, Film& film) {
    const size_t i = static_cast<size_t>(y) * film.width + x;
    const Ray ray = camera.generate_ray(x + 0.5, y + 0.5);
    Hit hit;
    if (!context.scene.intersect(ray, hit)) return;  // AOVs stay zero for the sky
    const Material& m = context.materials[hit.material];
    const Vec3 n = dot(hit.shading_normal, ray.direction) < 0 ? hit.shading_normal : -hit.shading_normal;
    const Color albedo = m.type == MaterialType::Diffuse || m.type == MaterialType::Glossy || m.type == MaterialType::Water ? m.albedo : m.specular;
    film.depth[i] = static_cast<float>(hit.t);
    for (int c = 0; c < 3; ++c) {
        film.normal[3 * i + c] = static_cast<float>(n[c]);
        film.albedo[3 * i + c] = static_cast<float>(albedo[c]);
    }
    film.object_kind[i] = static_cast<float>(hit.kind);
    film.object_index[i] = static_cast<float>(hit.object);
}

}  // namespace

Film render_image(const PathContext& context, const Camera& camera, const RenderSettings& settings,
                  RenderStats* stats) {
    Film film;
    film.width = settings.width;
    film.height = settings.height;
    const size_t pixels = static_cast<size_t>(film.width) * film.height;
    film.rgb.assign(3 * pixels, 0.f);
    if (settings.aovs) {
        film.depth.assign(pixels, 0.f);
        film.normal.assign(3 * pixels, 0.f);
        film.albedo.assign(3 * pixels, 0.f);
        film.object_kind.assign(pixels, 0.f);
        film.object_index.assign(pixels, 0.f);
    }
    const int tiles_x = (film.width + kTileSize - 1) / kTileSize;
    const int tiles_y = (film.height + kTileSize - 1) / kTileSize;
    const int tile_count = tiles_x * tiles_y;
    std::atomic<uint64_t> total_rays{0};
    Progress progress("render", static_cast<uint64_t>(tile_count), settings.quiet);
    const auto start = std::chrono::steady_clock::now();

    tbb::parallel_for(tbb::blocked_range<int>(0, tile_count, 1), [&](const tbb::blocked_range<int>& range) {
        for (int tile = range.begin(); tile != range.end(); ++tile) {
            uint64_t rays = 0;
            const int x0 = (tile % tiles_x) * kTileSize, y0 = (tile / tiles_x) * kTileSize;
            for (int y = y0; y < std::min(y0 + kTileSize, film.height); ++y) {
                for (int x = x0; x < std::min(x0 + kTileSize, film.width); ++x) {
                    // The pixel's own stream: the same numbers whichever thread renders it.
                    Rng rng(hash_keys(settings.seed, static_cast<uint64_t>(x), static_cast<uint64_t>(y)));
                    Color sum{0, 0, 0};
                    for (int s = 0; s < settings.spp; ++s) {
                        const double jx = rng.next_double(), jy = rng.next_double();
                        const Color L = trace_path(context, camera.generate_ray(x + jx, y + jy), rng, rays);
                        // A lone non-finite sample would poison the pixel; count it as black.
                        if (std::isfinite(L.x) && std::isfinite(L.y) && std::isfinite(L.z)) sum = sum + L;
                    }
                    const size_t i = static_cast<size_t>(y) * film.width + x;
                    const double inv = 1.0 / std::max(1, settings.spp);
                    for (int c = 0; c < 3; ++c) film.rgb[3 * i + c] = static_cast<float>(sum[c] * inv);
                    if (settings.aovs) {
                        fill_aovs(context, camera, x, y, film);
                        ++rays;
                    }
                }
            }
            total_rays += rays;
            progress.advance();
        }
    });
    progress.finish();
    if (stats) {
        stats->seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        stats->rays = total_rays.load();
    }
    return film;
}

}  // namespace citygen
