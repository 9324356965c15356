// Projection between WGS84 and the scene's local metres (x east, y north), centred on
// an origin. Transverse Mercator with its central meridian through the origin: scale
// error below 1e-5 within 30 km of it, so local distances are true to a centimetre.
#pragma once

#include <string>

#include "common/geometry.h"

namespace citygen {

class Projection {
public:
    Projection(double origin_lat, double origin_lon);

    Vec2 to_local(double lat, double lon) const;
    void to_wgs84(Vec2 local, double& lat, double& lon) const;

    double origin_lat() const { return origin_lat_; }
    double origin_lon() const { return origin_lon_; }
    static const char* name() { return "transverse-mercator"; }

private:
    double origin_lat_, origin_lon_;
    double origin_northing_;
};

}  // namespace citygen
