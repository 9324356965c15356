// The elevation grid between reading the DEM and the scene's height field: nodes over the
// scene's bounds in local metres, as read (no data kept as NaN) and then filled.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "common/geometry.h"

namespace citygen {

struct DemGrid {
    Vec2 origin;                   // node (0, 0); node (i, j) at origin + (i * cell, j * cell)
    double cell = 0;               // metres between nodes
    uint32_t nx = 0, ny = 0;
    std::vector<float> heights;    // nx * ny, i fastest, south to north; metres; NaN: no data
    std::vector<uint8_t> covered;  // 1 where the node lies within some DEM's samples

    size_t index(uint32_t i, uint32_t j) const { return static_cast<size_t>(j) * nx + i; }
    size_t size() const { return static_cast<size_t>(nx) * ny; }
};

}  // namespace citygen
