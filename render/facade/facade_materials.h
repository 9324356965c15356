// Which material each facade surface kind (render/facade/facade.h) is drawn with.
#pragma once

#include <array>
#include <cstdint>

#include "render/facade/facade.h"

namespace citygen {

// Indexed by FacadeSurface; values are MaterialIds (materials.h).
std::array<uint16_t, kFacadeSurfaceCount> facade_surface_materials();

}  // namespace citygen
