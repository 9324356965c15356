#include "render/lights/sky.h"

#include <algorithm>
#include <cmath>

#include "common/error.h"
#include "common/rng.h"

namespace citygen {

namespace {

constexpr double kSunAngularRadius = 0.265 * kPi / 180;

Vec3 direction_from(double azimuth_deg, double elevation_deg) {  // azimuth clockwise from north (+y)
    const double az = azimuth_deg * kPi / 180, el = elevation_deg * kPi / 180;
    return {std::sin(az) * std::cos(el), std::cos(az) * std::cos(el), std::sin(el)};
}

// CIE xyY to linear sRGB (D65).
Color xyY_to_rgb(double x, double y, double Y) {
    if (y <= 0) return {0, 0, 0};
    const double X = x / y * Y, Z = (1 - x - y) / y * Y;
    return {std::max(0.0, 3.2406 * X - 1.5372 * Y - 0.4986 * Z),
            std::max(0.0, -0.9689 * X + 1.8758 * Y + 0.0415 * Z),
            std::max(0.0, 0.0557 * X - 0.2040 * Y + 1.0570 * Z)};
}

// The Perez sky distribution, from cos(zenith angle), the angle to the sun and its cosine.
double perez(const double c[5], double cos_theta, double gamma, double cos_gamma) {
    cos_theta = std::max(cos_theta, 0.01);  // the model diverges at the horizon
    return (1 + c[0] * std::exp(c[1] / cos_theta)) * (1 + c[2] * std::exp(c[3] * gamma) + c[4] * cos_gamma * cos_gamma);
}

}  // namespace

TimeOfDay parse_time_of_day(const std::string& text) {
    if (text == "day") return TimeOfDay::Day;
    if (text == "sunset") return TimeOfDay::Sunset;
    if (text == "night") return TimeOfDay::Night;
    if (text == "dusk") return TimeOfDay::Dusk;
    throw Error("--time: expected day, sunset, dusk or night, got '" + text + "'");
}

Sky Sky::uniform(Color radiance) {
    Sky sky;
    sky.model_ = Model::Uniform;
    sky.uniform_ = radiance;
    return sky;
}

Sky Sky::uniform_with_sun(Color radiance, Vec3 sun_direction, double sun_angular_radius, Color sun_radiance) {
    Sky sky = uniform(radiance);
    sky.has_sun_ = true;
    sky.sun_direction_ = normalize(sun_direction);
    sky.sun_cos_radius_ = std::cos(sun_angular_radius);
    sky.sun_radiance_ = sun_radiance;
    return sky;
}

Sky Sky::daylight(TimeOfDay time) {
    SkySettings settings;
    settings.time = time;
    return for_settings(settings);
}

double default_sun_elevation(TimeOfDay time) {
    switch (time) {
        case TimeOfDay::Day: return 48;
        case TimeOfDay::Sunset: return 4;
        case TimeOfDay::Dusk: return -5;
        case TimeOfDay::Night: return -30;
    }
    return 48;
}

namespace {

double default_sun_azimuth(TimeOfDay time) {
    switch (time) {
        case TimeOfDay::Day: return 150;
        case TimeOfDay::Sunset: return 255;
        case TimeOfDay::Dusk:
        case TimeOfDay::Night: return 260;
    }
    return 150;
}

Color mix(Color a, Color b, double t) { return a * (1 - t) + b * t; }

// Full moon: about 0.25 lux on the ground, slightly blue to the eye.
constexpr double kMoonIlluminanceLux = 0.25;
constexpr double kNitsPerUnit = 1000.0 / 0.06;  // the sky's unit (see set_preetham); lights/photometry.h

}  // namespace

Sky Sky::for_settings(const SkySettings& settings) {
    Sky sky;
    const double elevation = std::isnan(settings.sun_elevation) ? default_sun_elevation(settings.time)
                                                                : settings.sun_elevation;
    const double azimuth = std::isnan(settings.sun_azimuth) ? default_sun_azimuth(settings.time) : settings.sun_azimuth;
    sky.sun_elevation_deg_ = elevation;
    sky.sun_cos_radius_ = std::cos(kSunAngularRadius);
    sky.model_ = Model::Preetham;
    if (elevation > 0) {
        // Daylight: from the sunset's red, dim sun at 4 degrees to the day's at 30 and above.
        const double t = std::clamp((elevation - 4) / (30 - 4), 0.0, 1.0);
        const double turbidity = 4 - t;
        double sun_irradiance = 2.0 + t;
        if (elevation < 4) sun_irradiance *= elevation / 4;  // ever longer path through the air
        const Color sun_colour = mix({1.0, 0.48, 0.18}, {1.0, 0.95, 0.88}, t);
        sky.has_sun_ = true;
        sky.sun_direction_ = direction_from(azimuth, elevation);
        sky.sun_radiance_ = sun_colour * (sun_irradiance / sky.sun_solid_angle());
        sky.set_preetham(turbidity, sky.sun_direction_);
    } else {
        // Twilight: the sky of a sun at the horizon, fading ~2.5x per degree the sun sinks and
        // turning blue (ozone), over the dark starry night.
        sky.set_preetham(4, direction_from(azimuth, 1));
        sky.twilight_scale_ = std::pow(2.5, elevation - 1);
        sky.night_glow_ = true;
        if (settings.moon) {
            sky.has_sun_ = true;
            sky.sun_direction_ = direction_from(azimuth + 170, 35);
            sky.sun_radiance_ = Color{0.85, 0.92, 1.08} * (kMoonIlluminanceLux / kNitsPerUnit / sky.sun_solid_angle());
        }
    }
    return sky;
}

void Sky::set_preetham(double turbidity, Vec3 sun_direction) {
    preetham_sun_ = sun_direction;
    // Preetham, Shirley, Smits: "A practical analytic model for daylight" (1999), appendix.
    const double T = turbidity;
    const double coefficients[3][5] = {
        {0.1787 * T - 1.4630, -0.3554 * T + 0.4275, -0.0227 * T + 5.3251, 0.1206 * T - 2.5771, -0.0670 * T + 0.3703},
        {-0.0193 * T - 0.2592, -0.0665 * T + 0.0008, -0.0004 * T + 0.2125, -0.0641 * T - 0.8989, -0.0033 * T + 0.0452},
        {-0.0167 * T - 0.2608, -0.0950 * T + 0.0092, -0.0079 * T + 0.2102, -0.0441 * T - 1.6537, -0.0109 * T + 0.0529}};
    std::copy(&coefficients[0][0], &coefficients[0][0] + 15, &perez_[0][0]);
    const double ts = std::acos(std::clamp(sun_direction.z, -1.0, 1.0));
    for (int i = 0; i < 3; ++i) perez_at_zenith_[i] = perez(perez_[i], 1, ts, std::cos(ts));
    const double chi = (4.0 / 9.0 - T / 120.0) * (kPi - 2 * ts);
    zenith_[0] = (4.0453 * T - 4.9710) * std::tan(chi) - 0.2155 * T + 2.4192;  // kcd/m^2
    const double ts2 = ts * ts, ts3 = ts2 * ts, T2 = T * T;
    zenith_[1] = T2 * (0.00166 * ts3 - 0.00375 * ts2 + 0.00209 * ts) +
                 T * (-0.02903 * ts3 + 0.06377 * ts2 - 0.03202 * ts + 0.00394) +
                 (0.11693 * ts3 - 0.21196 * ts2 + 0.06052 * ts + 0.25886);
    zenith_[2] = T2 * (0.00275 * ts3 - 0.00610 * ts2 + 0.00317 * ts) +
                 T * (-0.04214 * ts3 + 0.08970 * ts2 - 0.04153 * ts + 0.00516) +
                 (0.15346 * ts3 - 0.26756 * ts2 + 0.06670 * ts + 0.26688);
    // Our radiance unit: 1 kcd/m^2 of sky luminance -> 0.06, so a clear zenith is ~0.3 and the
    // sun (3 units of irradiance) dominates as it does outdoors.
    sky_scale_ = 0.06;
}

double Sky::sun_solid_angle() const { return 2 * kPi * (1 - sun_cos_radius_); }

Color Sky::radiance(Vec3 dir, bool seen_directly) const {
    switch (model_) {
        case Model::Uniform: return uniform_;
        case Model::Preetham: {
            if (!night_glow_) return preetham(dir);
            // Twilight turns blue as the sun sinks (ozone absorbs the red), over the night sky.
            const double blue = std::clamp((1 - sun_elevation_deg_) / 5, 0.0, 1.0);
            const Color tint = Color{1, 1, 1} * (1 - blue) + Color{0.3, 0.55, 1.6} * blue;
            return preetham(dir) * tint * twilight_scale_ + night(dir, seen_directly);
        }
        case Model::Night: return night(dir, seen_directly);
    }
    return uniform_;
}

Color Sky::preetham(Vec3 dir) const {
    // Below the horizon (past the ground plane) a darkened horizon colour stands in for the land.
    const bool below = dir.z < 0;
    Vec3 d = dir;
    if (d.z < 0.001) d = normalize(Vec3{d.x, d.y, 0.001});
    const double cos_gamma = std::clamp(dot(d, preetham_sun_), -1.0, 1.0);
    const double gamma = std::acos(cos_gamma);
    double value[3];
    for (int i = 0; i < 3; ++i) value[i] = zenith_[i] * perez(perez_[i], d.z, gamma, cos_gamma) / perez_at_zenith_[i];
    Color c = xyY_to_rgb(value[1], value[2], value[0] * sky_scale_);
    return below ? c * 0.3 : c;
}

Color Sky::night(Vec3 dir, bool stars) const {
    const double up = std::max(0.0, dir.z);
    // A dark blue zenith (~0.03 cd/m^2) and a warm glow of city light near the horizon
    // (~0.3 cd/m^2), in the sky's unit (16,667 cd/m^2).
    Color c = Color{1.2e-6, 1.6e-6, 3.0e-6} + Color{2.2e-5, 1.7e-5, 1.2e-5} * std::pow(1 - up, 8);
    if (dir.z <= 0) return c * 0.3;
    if (!stars) return c;
    // Stars: the sphere is cut into cells of about 0.25 degrees in azimuth x sin(elevation); a
    // hashed few hold a star whose small disc sits at a hashed spot in the cell.
    constexpr double kCellsAround = 1440, kCellsUp = 460;
    const double u = (std::atan2(dir.y, dir.x) / (2 * kPi) + 0.5) * kCellsAround;
    const double v = dir.z * kCellsUp;
    const int64_t cu = static_cast<int64_t>(u), cv = static_cast<int64_t>(v);
    const uint64_t h = hash_keys(0x5eedull, static_cast<uint64_t>(cu), static_cast<uint64_t>(cv));
    if (hash_to_unit(h) > 0.012) return c;
    const double su = cu + 0.2 + 0.6 * hash_to_unit(mix64(h)), sv = cv + 0.2 + 0.6 * hash_to_unit(mix64(h + 1));
    const double du = (u - su) / kCellsAround * 2 * kPi * std::sqrt(std::max(0.0, 1 - dir.z * dir.z));
    const double dv = (v - sv) / kCellsUp;
    const double radius = 0.0006;  // radians
    if (du * du + dv * dv > radius * radius) return c;
    // A bright star (magnitude 0, 2.5e-6 lux) over its disc is ~2 cd/m^2, 1.3e-4 units.
    const double brightness = 1e-4 * (0.2 + 2.0 * std::pow(hash_to_unit(mix64(h + 2)), 4));
    const double warm = hash_to_unit(mix64(h + 3));
    return c + Color{0.8 + 0.2 * warm, 0.85, 1.0 - 0.2 * warm} * brightness;
}

}  // namespace citygen
