#include "render/production/render_frames.h"

#include <algorithm>
#include <chrono>
#include <cstdio>

#include "render/film/image_output.h"

namespace citygen {

namespace {

// Copies the pixels of `region` (in frame coordinates) out of `film`.
Film crop(const Film& film, const PixelRegion& region) {
    Film out;
    out.width = region.width();
    out.height = region.height();
    out.x0 = region.x0;
    out.y0 = region.y0;
    auto copy = [&](const std::vector<float>& from, std::vector<float>& to, int channels) {
        if (from.empty()) return;
        to.resize(static_cast<size_t>(out.width) * out.height * channels);
        for (int y = 0; y < out.height; ++y) {
            const size_t src = (static_cast<size_t>(y + region.y0 - film.y0) * film.width + (region.x0 - film.x0)) * channels;
            std::copy_n(from.begin() + src, static_cast<size_t>(out.width) * channels,
                        to.begin() + static_cast<size_t>(y) * out.width * channels);
        }
    };
    copy(film.rgb, out.rgb, 3);
    copy(film.raw_rgb, out.raw_rgb, 3);
    copy(film.depth, out.depth, 1);
    copy(film.normal, out.normal, 3);
    copy(film.albedo, out.albedo, 3);
    copy(film.object_kind, out.object_kind, 1);
    copy(film.object_index, out.object_index, 1);
    copy(film.guide_albedo, out.guide_albedo, 3);
    copy(film.guide_normal, out.guide_normal, 3);
    copy(film.guide_depth, out.guide_depth, 1);
    copy(film.guide_direct, out.guide_direct, 3);
    copy(film.guide_variance, out.guide_variance, 1);
    copy(film.guide_sample_direct, out.guide_sample_direct, 3);
    return out;
}

}  // namespace

Film render_view(const PathContext& context, const Camera& camera, const RenderSettings& settings, bool denoise,
                 double exposure, RenderStats* stats) {
    // Shadow rays of lamp and window samples too dim to see at this exposure: roulette (integrator.h).
    PathContext traced = context;
    traced.settings.shadow_roulette = shadow_roulette_for(exposure);
    if (!denoise) return render_image(traced, camera, settings, stats);
    const PixelRegion region = render_region(settings);
    const DenoiseSettings denoise_settings;
    const int margin = denoise_margin(denoise_settings);
    RenderSettings wider = settings;
    wider.aovs = true;  // the object ids
    wider.denoise_guides = true;
    wider.region = {std::max(0, region.x0 - margin), std::max(0, region.y0 - margin),
                    std::min(settings.width, region.x1 + margin), std::min(settings.height, region.y1 + margin)};
    Film film = render_image(traced, camera, wider, stats);
    const auto filter_start = std::chrono::steady_clock::now();
    citygen::denoise(film, exposure, denoise_settings);
    if (stats) stats->denoise_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - filter_start).count();
    Film out = crop(film, region);
    if (!settings.aovs) {
        out.depth.clear();
        out.normal.clear();
        out.albedo.clear();
        out.object_kind.clear();
        out.object_index.clear();
    }
    return out;
}

void render_animation(const PathContext& context, const Animation& animation, const RenderSettings& settings,
                      bool denoise, const std::function<double(const Camera&)>& exposure_for) {
    using Clock = std::chrono::steady_clock;
    const Clock::time_point start = Clock::now();
    const int count = animation.frames.count();
    for (int k = 0; k < count; ++k) {
        const int frame = animation.frames.first + k;
        const CameraKey key = animation.view(frame / animation.fps);
        const Camera camera = Camera::look_at(key.position, key.look_at, key.fov, settings.width, settings.height);
        const std::string path = frame_file_name(animation.output_pattern, frame);
        const double exposure = exposure_for(camera);
        const Film film = render_view(context, camera, settings, denoise, exposure);
        write_image(film, path, exposure);
        if (!settings.quiet) {
            const double elapsed = std::chrono::duration<double>(Clock::now() - start).count();
            const double eta = elapsed / (k + 1) * (count - k - 1);
            std::fprintf(stderr, "render: frame %d of %d (frame %d, %s) done; %.1fs so far, ETA %.1fs\n", k + 1, count,
                         frame, path.c_str(), elapsed, eta);
        }
    }
}

}  // namespace citygen
