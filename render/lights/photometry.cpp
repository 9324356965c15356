#include "render/lights/photometry.h"

#include <algorithm>
#include <cmath>

#include "render/materials/bsdf.h"

namespace citygen {

Color blackbody_color(double kelvin) {
    const double T = std::clamp(kelvin, 1667.0, 25000.0);
    const double t1 = 1e3 / T, t2 = t1 * t1, t3 = t2 * t1;
    const double x = T <= 4000 ? -0.2661239 * t3 - 0.2343589 * t2 + 0.8776956 * t1 + 0.179910
                               : -3.0258469 * t3 + 2.1070379 * t2 + 0.2226347 * t1 + 0.240390;
    const double x2 = x * x, x3 = x2 * x;
    const double y = T <= 2222   ? -1.1063814 * x3 - 1.34811020 * x2 + 2.18555832 * x - 0.20219683
                     : T <= 4000 ? -0.9549476 * x3 - 1.37418593 * x2 + 2.09137015 * x - 0.16748867
                                 : 3.0817580 * x3 - 5.87338670 * x2 + 3.75112997 * x - 0.37001483;
    const double X = x / y, Y = 1, Z = (1 - x - y) / y;
    Color c{std::max(0.0, 3.2406 * X - 1.5372 * Y - 0.4986 * Z), std::max(0.0, -0.9689 * X + 1.8758 * Y + 0.0415 * Z),
            std::max(0.0, 0.0557 * X - 0.2040 * Y + 1.0570 * Z)};
    return c * (1 / luminance(c));
}

}  // namespace citygen
