#include "denoise.h"

#include <cmath>
#include <vector>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "error.h"

namespace citygen {

int denoise_margin(const DenoiseSettings& settings) { return 2 * ((1 << settings.levels) - 1); }

void denoise(Film& film, double exposure, const DenoiseSettings& settings) {
    const int width = film.width, height = film.height;
    const size_t pixels = static_cast<size_t>(width) * height;
    if (film.depth.size() != pixels) throw Error("--denoise needs the AOVs of the film");
    film.raw_rgb = film.rgb;
    constexpr double kernel[5] = {1.0 / 16, 1.0 / 4, 3.0 / 8, 1.0 / 4, 1.0 / 16};

    // The colour weight compares display-like values x / (1 + x), so a bright sun glint and a dark
    // corner get comparable tolerances.
    std::vector<float> display(3 * pixels);
    std::vector<float> current = film.rgb, next(3 * pixels);
    auto compress = [&](const std::vector<float>& rgb) {
        for (size_t i = 0; i < 3 * pixels; ++i) {
            const double x = std::max(0.0, rgb[i] * exposure);
            display[i] = static_cast<float>(x / (1 + x));
        }
    };
    const double inv_normal = 1 / (settings.sigma_normal * settings.sigma_normal);
    const double inv_albedo = 1 / (settings.sigma_albedo * settings.sigma_albedo);

    for (int level = 0; level < settings.levels; ++level) {
        const int step = 1 << level;
        const double sigma_color = settings.sigma_color / step;
        const double inv_color = 1 / (sigma_color * sigma_color);
        compress(current);
        tbb::parallel_for(tbb::blocked_range<int>(0, height), [&](const tbb::blocked_range<int>& rows) {
            for (int y = rows.begin(); y != rows.end(); ++y) {
                for (int x = 0; x < width; ++x) {
                    const size_t p = static_cast<size_t>(y) * width + x;
                    // Sums of w * (c_q - c_p): a constant image stays exactly constant.
                    double sum_w = 0, delta[3] = {0, 0, 0};
                    for (int dy = -2; dy <= 2; ++dy) {
                        const int qy = y + dy * step;
                        if (qy < 0 || qy >= height) continue;
                        for (int dx = -2; dx <= 2; ++dx) {
                            const int qx = x + dx * step;
                            if (qx < 0 || qx >= width) continue;
                            const size_t q = static_cast<size_t>(qy) * width + qx;
                            if (film.object_kind[q] != film.object_kind[p] || film.object_index[q] != film.object_index[p])
                                continue;
                            double color2 = 0, normal2 = 0, albedo2 = 0;
                            for (int c = 0; c < 3; ++c) {
                                const double dc = display[3 * q + c] - display[3 * p + c];
                                const double dn = film.normal[3 * q + c] - film.normal[3 * p + c];
                                const double da = film.albedo[3 * q + c] - film.albedo[3 * p + c];
                                color2 += dc * dc;
                                normal2 += dn * dn;
                                albedo2 += da * da;
                            }
                            const double tap_distance = step * std::max(std::abs(dx), std::abs(dy));
                            const double depth_tolerance =
                                settings.sigma_depth * std::max(film.depth[p], film.depth[q]) * tap_distance + 1e-6;
                            const double depth_ratio = (film.depth[q] - film.depth[p]) / depth_tolerance;
                            const double w = kernel[dx + 2] * kernel[dy + 2] *
                                             std::exp(-color2 * inv_color - normal2 * inv_normal -
                                                      albedo2 * inv_albedo - depth_ratio * depth_ratio);
                            sum_w += w;
                            for (int c = 0; c < 3; ++c) delta[c] += w * (current[3 * q + c] - current[3 * p + c]);
                        }
                    }
                    for (int c = 0; c < 3; ++c)
                        next[3 * p + c] = static_cast<float>(current[3 * p + c] + delta[c] / sum_w);
                }
            }
        });
        current.swap(next);
    }
    film.rgb = current;
}

}  // namespace citygen
