#include "render/film/exposure.h"

#include <algorithm>
#include <cmath>

#include "render/lights/photometry.h"
#include "render/materials/bsdf.h"

namespace citygen {

namespace {
// Linear value that the filmic curve (image_output.cpp) shows as nearly white.
constexpr double kFilmicWhite = 8.0;
}  // namespace

double exposure_from_ev(double ev100) {
    const double saturating_nits = 1.2 * std::pow(2.0, ev100);
    return kFilmicWhite * kNitsPerRadianceUnit / saturating_nits;
}

double ev_from_exposure(double exposure) {
    return std::log2(kFilmicWhite * kNitsPerRadianceUnit / exposure / 1.2);
}

double auto_exposure(const Film& film) {
    const size_t pixels = film.rgb.size() / 3;
    if (pixels == 0) return 1;
    double log_sum = 0;
    const double floor = 1e-9;  // the darkest night sky is ~1e-7
    for (size_t i = 0; i < pixels; ++i) {
        const double y = luminance({film.rgb[3 * i], film.rgb[3 * i + 1], film.rgb[3 * i + 2]});
        log_sum += std::log(std::max(y, floor));
    }
    const double average = std::exp(log_sum / pixels);
    const double nits = average * kNitsPerRadianceUnit;
    // Mid-grey (0.18) from ~100 cd/m^2 up (day, sunset), falling to 0.015 by ~0.1 cd/m^2.
    const double key = 0.18 * std::clamp((std::log10(std::max(nits, 1e-9)) + 1.5) / 4.5, 0.08, 1.0);
    return key / average;
}

double metered_exposure(const PathContext& context, const Camera& camera, const RenderSettings& settings) {
    RenderSettings meter = settings;
    meter.width = std::min(settings.width, 160);
    meter.height = std::max(1, static_cast<int>(std::lround(static_cast<double>(settings.height) * meter.width /
                                                            settings.width)));
    meter.spp = 4;
    meter.region = PixelRegion{};
    meter.time_limit_seconds = 0;
    meter.aovs = false;
    meter.denoise_guides = false;
    meter.quiet = true;
    return auto_exposure(render_image(context, camera.resized(meter.width, meter.height), meter));
}

}  // namespace citygen
