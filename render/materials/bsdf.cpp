#include "render/materials/bsdf.h"

#include <algorithm>
#include <cmath>

namespace citygen {

namespace {


// Any orthonormal basis around n (Duff et al. 2017), taken in a fixed tilted frame. Duff's basis
// jumps where the normal's third coordinate changes sign; in world coordinates that is every
// wall (n.z = 0), so a wall normal off by one rounding (stored triangles vs procedural walls)
// would scatter in a different direction. Tilted, the jump sits on normals perpendicular to
// (0.36, 0.48, 0.8): no roof or ground, and walls only at two azimuths.
const Vec3 kFrameX{-0.8, 0.6, 0}, kFrameY{-0.48, -0.64, 0.6}, kFrameZ{0.36, 0.48, 0.8};

void basis(Vec3 world_n, Vec3& t, Vec3& b) {
    const Vec3 n{dot(world_n, kFrameX), dot(world_n, kFrameY), dot(world_n, kFrameZ)};
    const double sign = std::copysign(1.0, n.z);
    const double a = -1.0 / (sign + n.z);
    const double c = n.x * n.y * a;
    const Vec3 local_t{1 + sign * n.x * n.x * a, sign * c, -sign * n.x};
    const Vec3 local_b{c, sign + n.y * n.y * a, -n.y};
    t = kFrameX * local_t.x + kFrameY * local_t.y + kFrameZ * local_t.z;
    b = kFrameX * local_b.x + kFrameY * local_b.y + kFrameZ * local_b.z;
}

Vec3 around(Vec3 axis, double cos_theta, double phi) {
    Vec3 t, b;
    basis(axis, t, b);
    const double sin_theta = std::sqrt(std::max(0.0, 1 - cos_theta * cos_theta));
    return normalize(t * (sin_theta * std::cos(phi)) + b * (sin_theta * std::sin(phi)) + axis * cos_theta);
}

// Probability of picking the Phong lobe over the diffuse one.
double specular_choice(const Material& m) {
    const double s = luminance(m.specular), d = luminance(m.albedo);
    return s + d > 0 ? s / (s + d) : 0;
}

double phong_pdf(const Material& m, Vec3 n, Vec3 wo, Vec3 wi) {
    const double c = std::max(0.0, dot(reflect(wo, n), wi));
    return (m.exponent + 1) / (2 * kPi) * std::pow(c, m.exponent);
}

// The water's reflection lobe: cos^exponent of the angle to the mirror direction, normalised
// over the sphere (the part below the surface is lost, as light that a wave facet sends into
// the next wave).
double water_lobe_pdf(const Material& m, Vec3 n, Vec3 wo, Vec3 wi) { return phong_pdf(m, n, wo, wi); }

}  // namespace

double water_reflectance(const Material& m, double cos_o) {
    const double r0 = ((1 - m.ior) / (1 + m.ior)) * ((1 - m.ior) / (1 + m.ior));
    const double c = 1 - std::clamp(cos_o, 0.0, 1.0);
    return r0 + (1 - r0) * c * c * c * c * c;
}

double luminance(Color c) { return 0.2126 * c.x + 0.7152 * c.y + 0.0722 * c.z; }

Vec3 reflect(Vec3 wo, Vec3 n) { return n * (2 * dot(n, wo)) - wo; }

Vec3 sample_cone(Vec3 axis, double cos_max, double u1, double u2) {
    return around(axis, 1 - u1 * (1 - cos_max), 2 * kPi * u2);
}

Color bsdf_eval(const Material& m, Vec3 n, Vec3 wo, Vec3 wi) {
    if (dot(n, wi) <= 0 || dot(n, wo) <= 0) return {0, 0, 0};
    Color f = m.albedo * (1 / kPi);
    if (m.type == MaterialType::Water) {
        // The body, plus the reflection as a Phong lobe of total weight F around the mirror
        // direction: f cos_i is F times the lobe's pdf, so a sample of it weighs F like the
        // mirror it replaces (a cos_i in the lobe, as in Glossy, would darken the bright grazing
        // reflections a mirror gives).
        const double fresnel = water_reflectance(m, dot(n, wo));
        return f * (1 - fresnel) + m.specular * (fresnel * water_lobe_pdf(m, n, wo, wi) / dot(n, wi));
    }
    if (m.type == MaterialType::Glossy) {
        // Normalised modified Phong: energy conserving for any exponent.
        const double c = std::max(0.0, dot(reflect(wo, n), wi));
        f = f + m.specular * ((m.exponent + 2) / (2 * kPi) * std::pow(c, m.exponent));
    }
    return f;
}

double bsdf_pdf(const Material& m, Vec3 n, Vec3 wo, Vec3 wi) {
    const double cos_i = dot(n, wi);
    if (cos_i <= 0) return 0;
    if (m.type == MaterialType::Water) {
        if (dot(n, wo) <= 0) return 0;
        const double fresnel = water_reflectance(m, dot(n, wo));
        return (1 - fresnel) * cos_i / kPi + fresnel * water_lobe_pdf(m, n, wo, wi);
    }
    if (m.type != MaterialType::Glossy) return cos_i / kPi;
    const double ps = specular_choice(m);
    return (1 - ps) * cos_i / kPi + ps * phong_pdf(m, n, wo, wi);
}

bool bsdf_sample(const Material& m, Vec3 n, Vec3 wo, double u1, double u2, double u3, BsdfSample& out) {
    switch (m.type) {
        case MaterialType::Mirror:
            out.wi = reflect(wo, n);
            out.weight = m.specular;
            out.delta = true;
            out.pdf = 1;
            return true;
        case MaterialType::Glass: {
            // n is the outward normal here: decide whether we enter or leave.
            const double ior = m.ior;
            const bool entering = dot(wo, n) > 0;
            const Vec3 nn = entering ? n : -n;
            const double eta = entering ? 1 / ior : ior;
            const double cos_i = dot(nn, wo);
            const double sin2_t = eta * eta * (1 - cos_i * cos_i);
            out.delta = true;
            out.pdf = 1;
            out.weight = m.specular;
            if (sin2_t >= 1) {  // total internal reflection
                out.wi = reflect(wo, nn);
                return true;
            }
            const double cos_t = std::sqrt(1 - sin2_t);
            const double r0 = ((1 - ior) / (1 + ior)) * ((1 - ior) / (1 + ior));
            const double c = 1 - (entering ? cos_i : cos_t);  // Schlick uses the angle on the air side
            const double fresnel = r0 + (1 - r0) * c * c * c * c * c;
            // Choosing reflection with probability F makes the weight exactly the tint.
            if (u3 < fresnel) out.wi = reflect(wo, nn);
            else out.wi = normalize(wo * -eta + nn * (eta * cos_i - cos_t));
            return true;
        }
        case MaterialType::Water: {
            // The reflection lobe with probability F, else the body's cosine lobe.
            const double cos_o = dot(n, wo);
            if (cos_o <= 0) return false;
            if (u3 < water_reflectance(m, cos_o)) out.wi = around(reflect(wo, n), std::pow(u1, 1 / (m.exponent + 1)), 2 * kPi * u2);
            else out.wi = around(n, std::sqrt(u1), 2 * kPi * u2);
            const double cos_i = dot(n, out.wi);
            if (cos_i <= 0) return false;  // the lobe reaches below the surface at grazing angles
            out.delta = false;
            out.pdf = bsdf_pdf(m, n, wo, out.wi);
            if (!(out.pdf > 0)) return false;
            out.weight = bsdf_eval(m, n, wo, out.wi) * (cos_i / out.pdf);
            return true;
        }
        case MaterialType::Diffuse:
        case MaterialType::Glossy: {
            const double ps = m.type == MaterialType::Glossy ? specular_choice(m) : 0;
            if (u3 < ps) out.wi = around(reflect(wo, n), std::pow(u1, 1 / (m.exponent + 1)), 2 * kPi * u2);
            else out.wi = around(n, std::sqrt(u1), 2 * kPi * u2);  // cosine-weighted
            const double cos_i = dot(n, out.wi);
            if (cos_i <= 0) return false;
            out.delta = false;
            out.pdf = bsdf_pdf(m, n, wo, out.wi);
            if (!(out.pdf > 0)) return false;
            out.weight = bsdf_eval(m, n, wo, out.wi) * (cos_i / out.pdf);
            return true;
        }
    }
    return false;
}

}  // namespace citygen
