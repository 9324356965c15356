#include "common/projection.h"

#include <GeographicLib/TransverseMercator.hpp>

namespace citygen {

namespace {
// Scale factor 1 on the central meridian: local metres are true metres there.
const GeographicLib::TransverseMercator& tm() {
    static const GeographicLib::TransverseMercator projection(
        GeographicLib::Constants::WGS84_a(), GeographicLib::Constants::WGS84_f(), 1.0);
    return projection;
}
}  // namespace

Projection::Projection(double origin_lat, double origin_lon)
    : origin_lat_(origin_lat), origin_lon_(origin_lon) {
    double x = 0;
    tm().Forward(origin_lon_, origin_lat_, origin_lon_, x, origin_northing_);
}

Vec2 Projection::to_local(double lat, double lon) const {
    double x = 0, y = 0;
    tm().Forward(origin_lon_, lat, lon, x, y);
    return {x, y - origin_northing_};
}

void Projection::to_wgs84(Vec2 local, double& lat, double& lon) const {
    tm().Reverse(origin_lon_, local.x, local.y + origin_northing_, lat, lon);
}

}  // namespace citygen
