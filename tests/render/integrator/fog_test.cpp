// Ground fog: energy kept when it only scatters, free flights and transmittance agree, the
// phase function integrates to one.
#include <cmath>

#include <gtest/gtest.h>

#include "common/rng.h"
#include "render/film/render_image.h"
#include "render/geometry/build_render_scene.h"
#include "render/integrator/fog.h"
#include "tests/render/small_town.h"

using namespace citygen;
using namespace citygen::test;

TEST(WhiteFurnace, FogThatScattersWithoutAbsorbingKeepsItOne) {
    // Ground fog with scattering albedo one: a path only changes direction in it, so under a
    // uniform sky with white surfaces every pixel still sees exactly 1.
    const auto scene = build_render_scene(small_town(), GeometryModes{});
    const MaterialTable materials = all_white_diffuse();
    const Sky sky = Sky::uniform({1, 1, 1});
    RenderSettings r = tiny(8);
    r.integrator.fog.density = 0.03;
    r.integrator.fog.top_z = 40;
    const Film film = render_image({*scene, materials, sky, r.integrator}, view_of_town(r), r);
    expect_all_one(film);
}

TEST(Fog, TransmittanceAndFreeFlightAgree) {
    FogSettings fog;
    fog.density = 0.05;
    fog.top_z = 20;
    const Vec3 origin{0, 0, 2}, up = normalize(Vec3{1, 0, 1});
    // Up through the layer: inside for (20 - 2) * sqrt(2) metres.
    EXPECT_NEAR(fog.length_inside(origin, up, 1e30), 18 * std::sqrt(2.0), 1e-9);
    EXPECT_NEAR(fog.length_inside({0, 0, 30}, normalize(Vec3{1, 0, -1}), 20 * std::sqrt(2.0)), 10 * std::sqrt(2.0),
                1e-9);
    // The share of free flights that get through is the transmittance.
    Rng rng(9);
    int through = 0;
    const int n = 200000;
    for (int i = 0; i < n; ++i) {
        double t;
        through += !fog.sample_scatter(origin, up, 1e30, rng.next_double(), &t);
    }
    const double expected = fog.transmittance(origin, up, 1e30);
    EXPECT_NEAR(through / double(n), expected, 4 * std::sqrt(expected * (1 - expected) / n));
    // The phase function integrates to one.
    double integral = 0;
    const int m = 400;
    for (int i = 0; i < m; ++i) {
        const double c = -1 + (i + 0.5) * 2.0 / m;
        integral += hg_phase(fog.g, {0, 0, 1}, {std::sqrt(1 - c * c), 0, c}) * 2 * kPi * 2.0 / m;
    }
    EXPECT_NEAR(integral, 1.0, 1e-3);
}
