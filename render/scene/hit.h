// Rays and the hit record every geometry mode fills in the same way, so the integrator and the
// AOVs never know whether a surface was stored as triangles or computed procedurally.
#pragma once

#include <cstdint>

#include "common/geometry.h"
#include "render/scene/geometry_mode.h"

namespace citygen {

struct Ray {
    Vec3 origin;
    Vec3 direction;  // unit length
    double tmin = 0;
    double tmax = 1e30;
};

struct Hit {
    double t = 0;               // distance along the (unit) ray direction
    Vec3 position;
    Vec3 geometric_normal;      // unit, on the surface's front (outside) side
    Vec3 shading_normal;        // unit, same side as geometric_normal
    uint16_t material = 0;      // index into the MaterialTable
    ObjectKind kind = ObjectKind::None;
    uint32_t object = 0;        // index of the object in the scene file's list of its kind
    // Facade panes (glass, balcony door, shop window): the wall (building_wall index) and the
    // cell (floor * 65536 + slot + 1; 0 elsewhere), which decide whether the window is lit.
    uint32_t wall = 0;
    uint32_t cell = 0;
};

}  // namespace citygen
