#include <algorithm>
#include <cmath>

#include "common/scene.h"

namespace citygen {

double HeightField::at(double x, double y) const {
    if (empty() || nx < 2 || ny < 2) return 0;
    // Grid coordinates, clamped to the grid: beyond its edge the edge's height.
    const double u = std::clamp((x - origin.x) / cell, 0.0, nx - 1.0);
    const double v = std::clamp((y - origin.y) / cell, 0.0, ny - 1.0);
    const uint32_t i = std::min(static_cast<uint32_t>(u), nx - 2), j = std::min(static_cast<uint32_t>(v), ny - 2);
    const double fu = u - i, fv = v - j;
    const size_t k = static_cast<size_t>(j) * nx + i;
    const double south = heights[k] * (1 - fu) + heights[k + 1] * fu;
    const double north = heights[k + nx] * (1 - fu) + heights[k + nx + 1] * fu;
    return south * (1 - fv) + north * fv;
}

}  // namespace citygen
