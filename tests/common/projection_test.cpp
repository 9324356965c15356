#include <gtest/gtest.h>

#include <cmath>

#include <GeographicLib/Geodesic.hpp>

#include "common/projection.h"

using namespace citygen;

TEST(Projection, OriginIsZero) {
    const Projection p(43.7376, 7.4225);
    const Vec2 o = p.to_local(43.7376, 7.4225);
    EXPECT_NEAR(o.x, 0, 1e-6);
    EXPECT_NEAR(o.y, 0, 1e-6);
}

TEST(Projection, AxesPointEastAndNorthInMetres) {
    const Projection p(52.48, 13.43);
    const Vec2 north = p.to_local(52.48 + 0.01, 13.43);
    const Vec2 east = p.to_local(52.48, 13.43 + 0.01);
    EXPECT_NEAR(north.x, 0, 1e-6);
    EXPECT_NEAR(north.y, 1113.0, 2.0);  // one hundredth of a degree of latitude
    EXPECT_NEAR(east.y, 0, 0.1);
    EXPECT_NEAR(east.x, 1113.2 * std::cos(52.48 * kPi / 180), 2.0);
}

TEST(Projection, RoundTripWithinOneCentimetreAtTenKilometres) {
    for (const auto& [lat, lon] : {std::pair{43.7376, 7.4225}, {47.64, -122.30}, {-33.9, 151.2}, {69.6, 18.9}}) {
        const Projection p(lat, lon);
        for (int k = 0; k < 16; ++k) {
            const double angle = k * kPi / 8;
            const Vec2 local(10000 * std::cos(angle), 10000 * std::sin(angle));
            double la = 0, lo = 0;
            p.to_wgs84(local, la, lo);
            const Vec2 back = p.to_local(la, lo);
            EXPECT_LT(length(back - local), 0.01) << lat << "," << lon << " angle " << angle;
            // Local metres are true metres: the geodesic distance from the origin is 10 km
            // within the projection's scale error (about 1e-6 at this distance).
            double geodesic = 0;
            GeographicLib::Geodesic::WGS84().Inverse(lat, lon, la, lo, geodesic);
            EXPECT_NEAR(geodesic, 10000, 0.05);
        }
    }
}
