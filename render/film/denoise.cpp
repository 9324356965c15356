#include "render/film/denoise.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "common/error.h"

namespace citygen {

namespace {

double luminance3(const float* c) { return 0.2126 * c[0] + 0.7152 * c[1] + 0.0722 * c[2]; }

constexpr double kKernel[5] = {1.0 / 16, 1.0 / 4, 3.0 / 8, 1.0 / 4, 1.0 / 16};

// The edge-stopping a-trous filter, level by level, over the light arriving at the surfaces, with
// its variance; the film's guides (object ids, normals, albedo, depth) stop it at edges.
class ATrousFilter {
public:
    ATrousFilter(const Film& film, const DenoiseSettings& settings)
        : film_(film), settings_(settings), width_(film.width), height_(film.height),
          inv_normal_(1 / (settings.sigma_normal * settings.sigma_normal)),
          inv_albedo_(1 / (settings.sigma_albedo * settings.sigma_albedo)) {}

    // The luminance tolerance follows the noise: a 3x3 blur of the variance (one pixel's own
    // estimate from a few samples is itself noisy), as in SVGF.
    void blur_variance(const std::vector<float>& variance, std::vector<float>& blurred) const {
        tbb::parallel_for(tbb::blocked_range<int>(0, height_), [&](const tbb::blocked_range<int>& rows) {
            for (int y = rows.begin(); y != rows.end(); ++y)
                for (int x = 0; x < width_; ++x) blurred[index(x, y)] = blurred_at(variance, x, y);
        });
    }

    // The filter at spacing `step` of `current` (and its variance) into `next`.
    void filter(int step, const std::vector<float>& current, const std::vector<float>& variance,
                const std::vector<float>& variance_blurred, std::vector<float>& next,
                std::vector<float>& next_variance) const {
        tbb::parallel_for(tbb::blocked_range<int>(0, height_), [&](const tbb::blocked_range<int>& rows) {
            for (int y = rows.begin(); y != rows.end(); ++y)
                for (int x = 0; x < width_; ++x)
                    filter_pixel(x, y, step, current, variance, variance_blurred, next, next_variance);
        });
    }

private:
    size_t index(int x, int y) const { return static_cast<size_t>(y) * width_ + x; }
    bool same_object(size_t p, size_t q) const {
        return film_.object_kind[q] == film_.object_kind[p] && film_.object_index[q] == film_.object_index[p];
    }
    // Whether q may inform p's noise estimate: the same object, facing the same way.
    bool alike(size_t p, size_t q) const {
        double normal2 = 0;
        for (int c = 0; c < 3; ++c) {
            const double dn = film_.guide_normal[3 * q + c] - film_.guide_normal[3 * p + c];
            normal2 += dn * dn;
        }
        return same_object(p, q) && normal2 < settings_.sigma_normal * settings_.sigma_normal;
    }

    float blurred_at(const std::vector<float>& variance, int x, int y) const {
        const size_t p = index(x, y);
        double sum = 0, sum_w = 0;
        for (int dy = -1; dy <= 1; ++dy)
            for (int dx = -1; dx <= 1; ++dx) {
                const int qx = x + dx, qy = y + dy;
                if (qx < 0 || qy < 0 || qx >= width_ || qy >= height_) continue;
                const size_t q = index(qx, qy);
                if (!alike(p, q)) continue;
                const double w = (dx == 0 ? 0.5 : 0.25) * (dy == 0 ? 0.5 : 0.25);
                sum += w * variance[q];
                sum_w += w;
            }
        return static_cast<float>(sum / sum_w);
    }

    // The edge-stopping weight of tap q (dx, dy taps away) for pixel p.
    double tap_weight(size_t p, size_t q, int dx, int dy, int step, double lum_p, double lum_tolerance,
                      const std::vector<float>& current) const {
        double normal2 = 0, albedo2 = 0;
        for (int c = 0; c < 3; ++c) {
            const double dn = film_.guide_normal[3 * q + c] - film_.guide_normal[3 * p + c];
            const double da = film_.guide_albedo[3 * q + c] - film_.guide_albedo[3 * p + c];
            normal2 += dn * dn;
            albedo2 += da * da;
        }
        const double tap_distance = step * std::max(std::abs(dx), std::abs(dy));
        const double depth_tolerance =
            settings_.sigma_depth * std::max(film_.guide_depth[p], film_.guide_depth[q]) * tap_distance + 1e-6;
        const double depth_ratio = (film_.guide_depth[q] - film_.guide_depth[p]) / depth_tolerance;
        return kKernel[dx + 2] * kKernel[dy + 2] *
               std::exp(-std::abs(luminance3(&current[3 * q]) - lum_p) / lum_tolerance - normal2 * inv_normal_ -
                        albedo2 * inv_albedo_ - depth_ratio * depth_ratio);
    }

    void filter_pixel(int x, int y, int step, const std::vector<float>& current, const std::vector<float>& variance,
                      const std::vector<float>& variance_blurred, std::vector<float>& next,
                      std::vector<float>& next_variance) const {
        const size_t p = index(x, y);
        if (film_.object_kind[p] == 0) {
            // The sky: seen directly, it has no path noise to remove (stars stay sharp).
            for (int c = 0; c < 3; ++c) next[3 * p + c] = current[3 * p + c];
            next_variance[p] = variance[p];
            return;
        }
        // The tolerance halves with each level, as the colour tolerance in Dammertz et al.: the
        // wide levels smooth what is flat but do not blur what the first levels kept (at a
        // constant tolerance, tree crowns, windows and lamp pools lost 0.4 dB to the fourth
        // level; two levels alone left walls blotchy).
        const double lum_p = luminance3(&current[3 * p]);
        const double lum_tolerance = settings_.sigma_luminance / step * std::sqrt(variance_blurred[p]) + 1e-4;
        // Sums of w * (c_q - c_p): a constant image stays exactly constant.
        double sum_w = 0, sum_w2_variance = 0, delta[3] = {0, 0, 0};
        for (int dy = -2; dy <= 2; ++dy) {
            const int qy = y + dy * step;
            if (qy < 0 || qy >= height_) continue;
            for (int dx = -2; dx <= 2; ++dx) {
                const int qx = x + dx * step;
                if (qx < 0 || qx >= width_) continue;
                const size_t q = index(qx, qy);
                if (!same_object(p, q)) continue;
                const double w = tap_weight(p, q, dx, dy, step, lum_p, lum_tolerance, current);
                sum_w += w;
                sum_w2_variance += w * w * variance[q];
                for (int c = 0; c < 3; ++c) delta[c] += w * (current[3 * q + c] - current[3 * p + c]);
            }
        }
        for (int c = 0; c < 3; ++c) next[3 * p + c] = static_cast<float>(current[3 * p + c] + delta[c] / sum_w);
        next_variance[p] = static_cast<float>(sum_w2_variance / (sum_w * sum_w));
    }

    const Film& film_;
    const DenoiseSettings& settings_;
    const int width_, height_;
    const double inv_normal_, inv_albedo_;
};

}  // namespace

int denoise_margin(const DenoiseSettings& settings) { return 2 * ((1 << settings.levels) - 1) + 1; }

void denoise(Film& film, double exposure, const DenoiseSettings& settings) {
    const size_t pixels = static_cast<size_t>(film.width) * film.height;
    if (film.object_kind.size() != pixels || film.guide_depth.size() != pixels || film.guide_variance.size() != pixels)
        throw Error("--denoise needs the film's id AOVs and guides");
    film.raw_rgb = film.rgb;
    // Emission and haze seen directly are noise-free: filter only the rest (no guide: none).
    const bool has_direct = film.guide_direct.size() == 3 * pixels;
    auto direct_at = [&](size_t k) { return has_direct ? film.guide_direct[k] : 0.f; };
    // The same light along the pixel's own sample rays: subtracting that instead also removes the
    // noise of where the samples fell (a lamp globe over part of the pixel), and the grid's
    // value goes back in.
    const bool has_sample_direct = has_direct && film.guide_sample_direct.size() == 3 * pixels;
    auto subtracted_at = [&](size_t k) { return has_sample_direct ? film.guide_sample_direct[k] : direct_at(k); };

    // Filter the light arriving at the surface (colour divided by the albedo guide), not the
    // colour: the texture lives in the noise-free albedo and comes back untouched afterwards.
    // Values are scaled by the exposure, so tolerances are in display units.
    std::vector<float> modulation(3 * pixels), current(3 * pixels), next(3 * pixels);
    std::vector<float> variance(pixels), next_variance(pixels), variance_blurred(pixels);
    for (size_t i = 0; i < pixels; ++i) {
        for (int c = 0; c < 3; ++c) {
            const size_t k = 3 * i + c;
            modulation[k] = film.guide_albedo[k] > 0.01f ? film.guide_albedo[k] : 1.f;
            current[k] = static_cast<float>((film.rgb[k] - subtracted_at(k)) * exposure / modulation[k]);
        }
        const double m = luminance3(&modulation[3 * i]);
        variance[i] = static_cast<float>(film.guide_variance[i] * exposure * exposure / (m * m));
    }
    const std::vector<float> input = current;
    const ATrousFilter filter(film, settings);
    for (int level = 0; level < settings.levels; ++level) {
        filter.blur_variance(variance, variance_blurred);
        filter.filter(1 << level, current, variance, variance_blurred, next, next_variance);
        current.swap(next);
        variance.swap(next_variance);
    }
    // The filtered light times the albedo, written as a change of the input so that an unchanged
    // pixel keeps its exact value.
    for (size_t i = 0; i < 3 * pixels; ++i)
        film.rgb[i] = static_cast<float>(film.rgb[i] + modulation[i] * (current[i] - input[i]) / exposure +
                                         (direct_at(i) - subtracted_at(i)));
}

}  // namespace citygen
