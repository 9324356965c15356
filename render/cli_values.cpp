#include "render/cli_values.h"

#include <cmath>
#include <sstream>

#include "common/error.h"
#include "common/scene_limits.h"

namespace citygen {

Vec3 parse_point(const std::string& text, const std::string& option) {
    std::stringstream in(text);
    double v[3];
    char comma1 = 0, comma2 = 0;
    in >> v[0] >> comma1 >> v[1] >> comma2 >> v[2];
    if (in.fail() || comma1 != ',' || comma2 != ',' || !(in >> std::ws).eof() || !std::isfinite(v[0]) ||
        !std::isfinite(v[1]) || !std::isfinite(v[2]))
        throw Error(option + ": expected X,Y,Z in metres, got '" + text + "'");
    // Far beyond any scene, ray arithmetic overflows (Embree asserts on its bounds).
    for (double c : v)
        if (std::fabs(c) > kMaxCoordinate)
            throw Error(option + ": '" + text + "' is more than " + std::to_string(static_cast<long>(kMaxCoordinate)) +
                        " m from the scene origin");
    return {v[0], v[1], v[2]};
}

void check_view(Vec3 camera, Vec3 look_at) {
    if (length(look_at - camera) < 1e-3)
        throw Error("--camera and --look-at are the same point; the camera needs a direction to look in");
}

PixelRegion parse_region(const std::string& text) {
    std::stringstream in(text);
    PixelRegion r;
    char c1 = 0, c2 = 0, c3 = 0;
    in >> r.x0 >> c1 >> r.y0 >> c2 >> r.x1 >> c3 >> r.y1;
    if (in.fail() || c1 != ',' || c2 != ',' || c3 != ',' || !(in >> std::ws).eof())
        throw Error("--region: expected X0,Y0,X1,Y1 in pixels, got '" + text + "'");
    if (r.empty()) throw Error("--region " + text + ": must be a non-empty rectangle (X0 < X1, Y0 < Y1)");
    return r;
}

}  // namespace citygen
