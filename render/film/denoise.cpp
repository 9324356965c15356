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

// The fit's unknowns: the light at the pixel, and its slopes along the differences of normal
// (3), relative depth, image position (2), albedo (3) and direct light.
constexpr int kUnknowns = 11;

// A neighbour whose weight is below e^-kNegligible (1e-6) is left out.
constexpr double kNegligible = 13.8;

// Solves the normal equations a x = b (a symmetric, lower triangle filled) for the first unknown
// of each of 3 right-hand sides by Cholesky; false when a is not positive definite.
bool solve_first_unknown(double a[kUnknowns][kUnknowns], const double b[kUnknowns][3], double first[3]) {
    double l[kUnknowns][kUnknowns];
    for (int i = 0; i < kUnknowns; ++i)
        for (int j = 0; j <= i; ++j) {
            double s = a[i][j];
            for (int k = 0; k < j; ++k) s -= l[i][k] * l[j][k];
            if (i == j) {
                if (!(s > 1e-12 * a[0][0])) return false;
                l[i][i] = std::sqrt(s);
            } else {
                l[i][j] = s / l[j][j];
            }
        }
    for (int c = 0; c < 3; ++c) {
        double z[kUnknowns], x[kUnknowns];
        for (int i = 0; i < kUnknowns; ++i) {
            double s = b[i][c];
            for (int k = 0; k < i; ++k) s -= l[i][k] * z[k];
            z[i] = s / l[i][i];
        }
        for (int i = kUnknowns - 1; i >= 0; --i) {
            double s = z[i];
            for (int k = i + 1; k < kUnknowns; ++k) s -= l[k][i] * x[k];
            x[i] = s / l[i][i];
        }
        first[c] = x[0];
    }
    return true;
}

class RegressionFilter {
public:
    // `light`: 3 per pixel, what is filtered; `variance`: of each pixel's mean luminance of it;
    // `direct`: the luminance of the noise-free direct light in the same units (a guide).
    RegressionFilter(const Film& film, const DenoiseSettings& settings, const std::vector<float>& light,
                     const std::vector<float>& variance, std::vector<float> direct)
        : film_(film), settings_(settings), light_(light), direct_(std::move(direct)), width_(film.width),
          height_(film.height), patch_luminance_(light.size() / 3), patch_variance_(light.size() / 3) {
        // A 3x3 patch's mean luminance: one pixel's own is too noisy to weigh a neighbour by.
        for (int y = 0; y < height_; ++y)
            for (int x = 0; x < width_; ++x) {
                double sum = 0, sum_variance = 0;
                for (int dy = -1; dy <= 1; ++dy)
                    for (int dx = -1; dx <= 1; ++dx) {
                        const size_t q = index(std::clamp(x + dx, 0, width_ - 1), std::clamp(y + dy, 0, height_ - 1));
                        sum += luminance3(&light[3 * q]);
                        sum_variance += variance[q];
                    }
                patch_luminance_[index(x, y)] = static_cast<float>(sum / 9);
                patch_variance_[index(x, y)] = static_cast<float>(sum_variance / 81);
            }
    }

    void filter(std::vector<float>& out) const {
        tbb::parallel_for(tbb::blocked_range<int>(0, height_), [&](const tbb::blocked_range<int>& rows) {
            for (int y = rows.begin(); y != rows.end(); ++y)
                for (int x = 0; x < width_; ++x) filter_pixel(x, y, &out[3 * index(x, y)]);
        });
    }

private:
    size_t index(int x, int y) const { return static_cast<size_t>(y) * width_ + x; }

    // Minus the log of the neighbour's weight in p's fit, and its features (differences from
    // p's guides).
    double tap_exponent(size_t p, size_t q, int dx, int dy, double features[kUnknowns]) const {
        const int radius = settings_.radius;
        double normal2 = 0, albedo2 = 0;
        features[0] = 1;
        for (int c = 0; c < 3; ++c) {
            const double dn = film_.guide_normal[3 * q + c] - film_.guide_normal[3 * p + c];
            const double da = film_.guide_albedo[3 * q + c] - film_.guide_albedo[3 * p + c];
            features[1 + c] = dn;
            features[7 + c] = da;
            normal2 += dn * dn;
            albedo2 += da * da;
        }
        const double depth_p = film_.guide_depth[p], depth_q = film_.guide_depth[q];
        features[4] = (depth_q - depth_p) / (depth_p + 1e-6);
        features[5] = static_cast<double>(dx) / radius;
        features[6] = static_cast<double>(dy) / radius;
        features[10] = direct_[q] - direct_[p];
        const double distance = std::max({std::abs(dx), std::abs(dy), 1});
        const double depth_ratio =
            (depth_q - depth_p) / (settings_.sigma_depth * std::max(depth_p, depth_q) * distance + 1e-6);
        // The squared difference of the patches beyond what noise alone would give, in units of
        // p's own noise: a neighbour brighter than that allows is left out however noisy it is
        // itself, so a firefly does not spread into a blob.
        const double patch_difference = patch_luminance_[q] - patch_luminance_[p];
        const double patch_noise = 2 * patch_variance_[p];
        const double luminance = std::max(0.0, patch_difference * patch_difference - patch_noise) /
                                 (settings_.sigma_luminance * settings_.sigma_luminance * patch_noise + 1e-8);
        return 2.0 * (dx * dx + dy * dy) / (radius * radius) + normal2 / (settings_.sigma_normal * settings_.sigma_normal) +
               albedo2 / (settings_.sigma_albedo * settings_.sigma_albedo) + depth_ratio * depth_ratio + luminance;
    }

    void filter_pixel(int x, int y, float* out) const {
        const size_t p = index(x, y);
        const float* light_p = &light_[3 * p];
        for (int c = 0; c < 3; ++c) out[c] = light_p[c];
        // The sky: seen directly, it has no path noise to remove (stars stay sharp).
        if (film_.object_kind[p] == 0) return;
        // The fit is of the neighbours' differences from p, so that a constant image stays
        // exactly constant.
        double a[kUnknowns][kUnknowns] = {}, b[kUnknowns][3] = {};
        const int radius = settings_.radius;
        for (int dy = -radius; dy <= radius; ++dy) {
            const int qy = y + dy;
            if (qy < 0 || qy >= height_) continue;
            for (int dx = -radius; dx <= radius; ++dx) {
                const int qx = x + dx;
                if (qx < 0 || qx >= width_) continue;
                const size_t q = index(qx, qy);
                if (film_.object_kind[q] == 0) continue;
                double f[kUnknowns];
                const double exponent = tap_exponent(p, q, dx, dy, f);
                if (exponent > kNegligible) continue;
                const double w = std::exp(-exponent);
                double difference[3];
                for (int c = 0; c < 3; ++c) difference[c] = w * (light_[3 * q + c] - light_p[c]);
                for (int i = 0; i < kUnknowns; ++i) {
                    const double wf = w * f[i];
                    for (int j = 0; j <= i; ++j) a[i][j] += wf * f[j];
                    for (int c = 0; c < 3; ++c) b[i][c] += f[i] * difference[c];
                }
            }
        }
        for (int i = 1; i < kUnknowns; ++i) a[i][i] += settings_.ridge * a[0][0];
        double change[3];
        if (!solve_first_unknown(a, b, change))
            for (int c = 0; c < 3; ++c) change[c] = b[0][c] / a[0][0];  // the weighted mean
        for (int c = 0; c < 3; ++c) out[c] = static_cast<float>(light_p[c] + change[c]);
    }

    const Film& film_;
    const DenoiseSettings& settings_;
    const std::vector<float>& light_;
    const std::vector<float> direct_;
    const int width_, height_;
    std::vector<float> patch_luminance_, patch_variance_;
};

}  // namespace

int denoise_margin(const DenoiseSettings& settings) { return settings.radius + 1; }

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
    std::vector<float> modulation(3 * pixels), light(3 * pixels), variance(pixels), direct(pixels);
    for (size_t i = 0; i < pixels; ++i) {
        float direct_rgb[3];
        for (int c = 0; c < 3; ++c) {
            const size_t k = 3 * i + c;
            modulation[k] = film.guide_albedo[k] > 0.01f ? film.guide_albedo[k] : 1.f;
            light[k] = static_cast<float>((film.rgb[k] - subtracted_at(k)) * exposure / modulation[k]);
            direct_rgb[c] = static_cast<float>(direct_at(k) * exposure / modulation[k]);
        }
        const double m = luminance3(&modulation[3 * i]);
        variance[i] = static_cast<float>(film.guide_variance[i] * exposure * exposure / (m * m));
        direct[i] = static_cast<float>(luminance3(direct_rgb));
    }
    std::vector<float> filtered(3 * pixels);
    RegressionFilter(film, settings, light, variance, std::move(direct)).filter(filtered);
    // The filtered light times the albedo, written as a change of the input so that an unchanged
    // pixel keeps its exact value.
    for (size_t i = 0; i < 3 * pixels; ++i)
        film.rgb[i] = static_cast<float>(film.rgb[i] + modulation[i] * (filtered[i] - light[i]) / exposure +
                                         (direct_at(i) - subtracted_at(i)));
}

}  // namespace citygen
