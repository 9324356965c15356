// BSDF sampling: directions continuous in the normal, Fresnel reflection of glass.
#include <cmath>

#include <gtest/gtest.h>

#include "render/materials/bsdf.h"
#include "render/materials/materials.h"

using namespace citygen;

TEST(Sampling, DirectionsAreContinuousInTheNormalAcrossWalls) {
    // A wall normal with z = +1e-12 or -1e-12 (one rounding apart, e.g. stored triangle vs
    // procedural wall) must scatter the same random numbers into nearly the same direction.
    Material diffuse{"white", MaterialType::Diffuse, {1, 1, 1}, {0, 0, 0}, 1, 1.5, {}};
    Material glossy = diffuse;
    glossy.type = MaterialType::Glossy;
    glossy.specular = {0.5, 0.5, 0.5};
    glossy.exponent = 50;
    for (const Material& m : {diffuse, glossy}) {
        for (double azimuth = 0; azimuth < 6.28; azimuth += 0.1) {
            const Vec3 up = normalize(Vec3{std::cos(azimuth), std::sin(azimuth), 1e-12});
            const Vec3 down = normalize(Vec3{std::cos(azimuth), std::sin(azimuth), -1e-12});
            const Vec3 wo = normalize(up + Vec3{0.2, -0.1, 0.4});
            for (double u : {0.1, 0.37, 0.62, 0.9}) {
                BsdfSample a, b;
                const bool ok_a = bsdf_sample(m, up, wo, u, 1 - u, u * u, a);
                const bool ok_b = bsdf_sample(m, down, wo, u, 1 - u, u * u, b);
                ASSERT_EQ(ok_a, ok_b);
                if (ok_a) {
                    EXPECT_LT(length(a.wi - b.wi), 1e-6) << m.name << " azimuth " << azimuth << " u " << u;
                }
            }
        }
    }
}

TEST(Glass, FresnelReflectsMoreAtGrazingAngles) {
    const Material glass = default_materials()[kGlass];
    const Vec3 n{0, 0, 1};
    auto reflected_fraction = [&](Vec3 wo) {
        int reflected = 0;
        for (int i = 0; i < 2000; ++i) {
            BsdfSample s;
            EXPECT_TRUE(bsdf_sample(glass, n, wo, 0.5, 0.5, (i + 0.5) / 2000, s));
            if (s.wi.z > 0) ++reflected;
        }
        return reflected / 2000.0;
    };
    EXPECT_NEAR(reflected_fraction({0, 0, 1}), 0.04, 0.002);  // ((1.5-1)/(1.5+1))^2
    EXPECT_GT(reflected_fraction(normalize(Vec3{1, 0, 0.05})), 0.5);
    // From inside beyond the critical angle: total internal reflection.
    EXPECT_EQ(reflected_fraction(normalize(Vec3{1, 0, -0.3})), 0.0);  // wi stays inside (z < 0)
}

TEST(Water, GlossyReflectionWithFresnelThatLightSamplingCanFind) {
    // Water reflects a lobe around the mirror direction, not a delta: next-event estimation of
    // the sun and lamps sees it (pdf and f finite and positive there), and a sample's weight
    // is the eval over the pdf. Over the hemisphere it returns F of the light plus the body's
    // share, as the mirror it replaced did.
    const Material sea = default_materials()[kSea];
    EXPECT_FALSE(is_delta(sea));
    const Vec3 n{0, 0, 1};
    for (const Vec3 wo : {normalize(Vec3{0.3, 0.1, 1}), normalize(Vec3{1, 0.2, 0.35})}) {
        const double fresnel = water_reflectance(sea, wo.z);
        const Vec3 mirror = reflect(wo, n);
        const double peak = fresnel * (sea.exponent + 1) / (2 * kPi);  // the lobe's share at its centre
        EXPECT_GT(bsdf_pdf(sea, n, wo, mirror), peak);
        EXPECT_GT(bsdf_eval(sea, n, wo, mirror).y * mirror.z, peak);
        Color sum{0, 0, 0};
        constexpr int kSide = 200;
        for (int i = 0; i < kSide; ++i)
            for (int j = 0; j < kSide; ++j) {
                BsdfSample s;
                if (!bsdf_sample(sea, n, wo, (i + 0.5) / kSide, (j + 0.5) / kSide, ((i * 7 + j * 13) % kSide + 0.5) / kSide, s))
                    continue;
                EXPECT_FALSE(s.delta);
                const Color f = bsdf_eval(sea, n, wo, s.wi);
                EXPECT_NEAR(s.weight.y, f.y * s.wi.z / s.pdf, 1e-9 * (1 + s.weight.y));
                EXPECT_NEAR(s.pdf, bsdf_pdf(sea, n, wo, s.wi), 1e-9 * s.pdf);
                sum = sum + s.weight;
            }
        const Color albedo = sum * (1.0 / (kSide * kSide));
        EXPECT_NEAR(albedo.y, fresnel + (1 - fresnel) * sea.albedo.y, 0.02 * (fresnel + sea.albedo.y)) << wo.z;
    }
}
