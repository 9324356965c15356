#include "render/integrator/fog.h"

#include <algorithm>
#include <cmath>

#include "render/materials/bsdf.h"

namespace citygen {

namespace {

// The parameter interval of the ray inside the half-space z <= top: [enter, leave].
void inside_interval(double top, Vec3 origin, Vec3 direction, double t_max, double* enter, double* leave) {
    *enter = 0;
    *leave = t_max;
    if (direction.z == 0) {
        if (origin.z > top) *leave = -1;
        return;
    }
    const double t = (top - origin.z) / direction.z;
    if (direction.z > 0) *leave = std::min(t_max, t);  // going up: inside until it crosses the top
    else *enter = std::max(0.0, t);                    // going down: inside from the crossing on
}
}  // namespace

double FogSettings::length_inside(Vec3 origin, Vec3 direction, double t_max) const {
    double enter, leave;
    inside_interval(top_z, origin, direction, t_max, &enter, &leave);
    return std::max(0.0, leave - enter);
}

double FogSettings::transmittance(Vec3 origin, Vec3 direction, double t_max) const {
    if (!on()) return 1;
    return std::exp(-density * length_inside(origin, direction, t_max));
}

bool FogSettings::sample_scatter(Vec3 origin, Vec3 direction, double t_max, double u, double* t) const {
    if (!on()) return false;
    double enter, leave;
    inside_interval(top_z, origin, direction, t_max, &enter, &leave);
    if (!(leave > enter)) return false;
    const double s = -std::log1p(-u) / density;
    if (enter + s >= leave) return false;
    *t = enter + s;
    return true;
}

double hg_phase(double g, Vec3 in, Vec3 out) {
    const double c = dot(in, out);
    const double denom = 1 + g * g - 2 * g * c;
    return (1 - g * g) / (4 * kPi * denom * std::sqrt(std::max(denom, 1e-12)));
}

Vec3 sample_hg(double g, Vec3 in, double u1, double u2) {
    double cos_theta;
    if (std::fabs(g) < 1e-3) {
        cos_theta = 1 - 2 * u1;
    } else {
        const double s = (1 - g * g) / (1 - g + 2 * g * u1);
        cos_theta = (1 + g * g - s * s) / (2 * g);
    }
    cos_theta = std::clamp(cos_theta, -1.0, 1.0);
    // sample_cone with cos_max = cos_theta at u1 = 1 gives exactly that angle around `in`.
    return sample_cone(in, cos_theta, 1.0, u2);
}

}  // namespace citygen
