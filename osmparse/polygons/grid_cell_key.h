// The hash-map key of a cell of a uniform grid, shared by the grids of osmparse's stages.
#pragma once

#include <cstdint>

namespace citygen {

// One key per cell (no two cells share a list) while cell coordinates stay below 2^31 in
// magnitude: projected metres over any extract divided by a cell of a metre or more.
inline int64_t grid_cell_key(int64_t cx, int64_t cy) {
    return static_cast<int64_t>((static_cast<uint64_t>(cx) << 32) ^ static_cast<uint32_t>(cy));
}

}  // namespace citygen
