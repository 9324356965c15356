// Light from the sky: an analytic daylight model (Preetham et al. 1999) with a sun disc for day
// and sunset, a dark sky with procedural stars and the moon for night, and a uniform sky for
// tests (the white furnace).
#pragma once

#include <cmath>
#include <string>

#include "render/materials/materials.h"

namespace citygen {

enum class TimeOfDay { Day, Sunset, Night, Dusk };
TimeOfDay parse_time_of_day(const std::string& text);  // throws citygen::Error

// The sky for a time of day, or for a sun placed by hand (--sun-elevation / --sun-azimuth,
// degrees; NaN: the time's default). The sun's elevation alone picks the sky: daylight above
// the horizon (redder and dimmer as it sinks), a twilight glow fading about 2.5x per degree
// below it, and the dark starry night under that. The moon (--moon) lights the night instead
// of the sun when the sun is below the horizon.
struct SkySettings {
    TimeOfDay time = TimeOfDay::Day;
    double sun_elevation = std::nan("");
    double sun_azimuth = std::nan("");  // clockwise from north (+y)
    bool moon = false;
};
double default_sun_elevation(TimeOfDay time);  // degrees
// Street lamps and lit windows are on when the sun is lower than this (degrees).
constexpr double kLightsOnBelowElevation = 1.0;

class Sky {
public:
    static Sky daylight(TimeOfDay time);
    static Sky for_settings(const SkySettings& settings);
    double sun_elevation() const { return sun_elevation_deg_; }  // degrees, even when below the horizon
    static Sky uniform(Color radiance);  // no sun
    // A uniform sky plus a sun disc of the given angular radius (radians), for tests.
    static Sky uniform_with_sun(Color radiance, Vec3 sun_direction, double sun_angular_radius, Color sun_radiance);

    // Radiance arriving from direction `dir` (unit, pointing away from the scene), without the
    // sun (or moon) disc, which is a separate light for next-event estimation. Stars (tiny and
    // bright) only show when `seen_directly` (camera or mirror paths): lit surfaces would only
    // turn them into fireflies for no visible light.
    Color radiance(Vec3 dir, bool seen_directly = true) const;

    bool has_sun() const { return has_sun_; }
    Vec3 sun_direction() const { return sun_direction_; }  // unit, towards the sun
    double sun_cos_radius() const { return sun_cos_radius_; }
    Color sun_radiance() const { return sun_radiance_; }
    bool in_sun_disc(Vec3 dir) const { return has_sun_ && dot(dir, sun_direction_) >= sun_cos_radius_; }
    double sun_solid_angle() const;
    // Exposure the film applies before tone mapping, so day and night both land mid-grey.

private:
    enum class Model { Uniform, Preetham, Night } model_ = Model::Uniform;
    Color uniform_{1, 1, 1};
    bool has_sun_ = false;
    Vec3 sun_direction_{0, 0, 1};
    double sun_cos_radius_ = 1;
    Color sun_radiance_{0, 0, 0};
    // Preetham: Perez coefficients A..E for Y, x, y and the zenith values.
    double perez_[3][5] = {};
    double zenith_[3] = {};
    double sky_scale_ = 1;
    double perez_at_zenith_[3] = {1, 1, 1};  // F(0, sun zenith angle): normalises to the zenith values
    double sun_elevation_deg_ = 90;
    Vec3 preetham_sun_{0, 0, 1};  // the sun the Preetham sky is computed for (at least 1 degree up)
    double twilight_scale_ = 1;   // Preetham sky (sun at the horizon) times this, below the horizon
    bool night_glow_ = false;     // the dark starry sky adds beneath the Preetham/twilight sky
    void set_preetham(double turbidity, Vec3 sun_direction);

    Color preetham(Vec3 dir) const;
    Color night(Vec3 dir, bool stars) const;
};

}  // namespace citygen
