// An estimate of what a render will need, checked before any geometry is built, so a scene that
// cannot fit is refused with the figure instead of growing until the kernel kills the process.
#pragma once

#include <cstdint>
#include <string>

#include "common/scene.h"
#include "render/facade/facade.h"
#include "render/film/render_image.h"
#include "render/scene/geometry_mode.h"

namespace citygen {

struct MemoryEstimate {
    double stored_triangles = 0;       // triangles of the stored classes
    double procedural_primitives = 0;  // Embree user primitives of the procedural classes
    double image_bytes = 0;            // film and the encoded image
    double bytes = 0;                  // all of it, with Embree's BVH and build scratch
};

// The triangles facade_mesh.h makes of a wall (wall_triangle_count), in O(1) instead of O(cells).
double wall_triangle_estimate(const WallLayout& layout);

MemoryEstimate estimate_render_memory(const Scene& scene, const GeometryModes& modes, const FacadeOptions& facades,
                                      const RenderSettings& settings);

// Bytes this process may still allocate: the least of the memory the system has available,
// the address-space limit (ulimit -v) and the cgroup limit, each minus what is in use.
double available_memory_bytes();

// Throws citygen::Error when the estimate exceeds available_memory_bytes(), saying how much the
// render would need.
void check_memory_fits(const MemoryEstimate& estimate);

}  // namespace citygen
