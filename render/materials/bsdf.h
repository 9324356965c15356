// Scattering at a surface for each MaterialType: evaluation, pdf and importance sampling.
// Directions point away from the surface; `n` is the geometric normal on the side of `wo`
// (except for glass, which needs to know the true outside and gets the outward normal).
#pragma once

#include "render/materials/materials.h"

namespace citygen {

struct BsdfSample {
    Vec3 wi;
    Color weight;     // f * |cos| / pdf (for delta lobes: the reflectance or transmittance)
    double pdf = 0;   // solid-angle pdf; meaningless when delta
    bool delta = false;
};

// True for materials whose scattering is a delta distribution (no next-event estimation).
inline bool is_delta(const Material& m) { return m.type == MaterialType::Mirror || m.type == MaterialType::Glass; }

// f(wo, wi) for non-delta materials.
Color bsdf_eval(const Material& m, Vec3 n, Vec3 wo, Vec3 wi);
double bsdf_pdf(const Material& m, Vec3 n, Vec3 wo, Vec3 wi);
// Samples wi from two uniform numbers and a third for the lobe choice. False when the path
// ends (the sample fell below the surface).
bool bsdf_sample(const Material& m, Vec3 n, Vec3 wo, double u1, double u2, double u3, BsdfSample& out);

// A unit vector in the cone of half-angle acos(cos_max) around `axis` (uniform in solid angle).
Vec3 sample_cone(Vec3 axis, double cos_max, double u1, double u2);

// Schlick's Fresnel reflectance of a water surface seen at cos_o from its normal.
double water_reflectance(const Material& m, double cos_o);

Vec3 reflect(Vec3 wo, Vec3 n);  // mirror of wo about n
double luminance(Color c);

}  // namespace citygen
