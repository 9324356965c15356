// Participating media along paths: optional homogeneous ground fog (--fog DENSITY), traced
// with single and multiple scattering from the sun and the lamps (lamp haloes), and the
// aerial perspective of clear air on camera rays (far districts fade into the horizon's haze).
//
// The fog fills the air from the ground up to `top_z`; it scatters (Henyey-Greenstein phase
// function, forward-peaked like water droplets) and never absorbs, so a white furnace stays
// white. Distances are sampled in proportion to transmittance, so the path throughput is
// unchanged by a scattering event and only shadow rays need transmittance explicitly.
#pragma once

#include <cmath>

#include "common/geometry.h"

namespace citygen {

struct FogSettings {
    double density = 0;   // scattering coefficient, 1/m (0: no fog); extinction = scattering
    double top_z = 0;     // the fog fills z <= top_z
    double g = 0.7;       // Henyey-Greenstein anisotropy (forward scattering: haloes)
    bool on() const { return density > 0; }

    // Length of the part of the ray segment [0, t_max] (unit direction) inside the fog.
    double length_inside(Vec3 origin, Vec3 direction, double t_max) const;
    double transmittance(Vec3 origin, Vec3 direction, double t_max) const;
    // Free-flight sampling: true and the distance t < t_max of a scattering event, or false when
    // the ray gets through (with probability equal to the transmittance).
    bool sample_scatter(Vec3 origin, Vec3 direction, double t_max, double u, double* t) const;
};

// Henyey-Greenstein: pdf over solid angle of scattering from direction `in` (propagation) to
// `out`, and sampling `out` (the sample's weight is 1: value == pdf).
double hg_phase(double g, Vec3 in, Vec3 out);
Vec3 sample_hg(double g, Vec3 in, double u1, double u2);

// Aerial perspective on a camera ray that hit a surface at distance `distance`: the fraction of
// the surface's light that arrives, for a clear-air extinction (1/m; 3.912 / visibility).
inline double aerial_transmittance(double extinction, double distance) { return std::exp(-extinction * distance); }

}  // namespace citygen
