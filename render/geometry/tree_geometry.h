// Trees (format 1.1) in both geometry modes: a trunk (vertical cylinder) and a crown (an
// ellipsoid shell with a noise cut-out at leaf-clump scale, around an opaque inner core), so
// light falls through in patches and the crown shows leaf-scale detail.
//   - stored: triangles (an 8-sided trunk, a 16 x 10 shell, a 8 x 5 core); an Embree filter
//     function cuts the shell where the leaf noise (at the point moved onto the true
//     ellipsoid) says "gap";
//   - procedural: one user primitive per tree, 20 bytes of our own; the callback intersects
//     the cylinder and the two ellipsoids analytically with the same cut-out.
// The shape and the cut-out are defined once (tree_shape, leaf_present) for both.
#pragma once

#include <memory>

#include "common/scene.h"
#include "render/scene/render_scene.h"

namespace citygen {

struct TreeShape {
    Vec3 base;                    // foot of the trunk
    double trunk_radius = 0.2, trunk_top = 3;   // trunk height above base (reaches into the crown)
    Vec3 crown_centre;
    double crown_radius = 3, crown_half_height = 3;  // ellipsoid semi-axes (horizontal, vertical)
    uint16_t leaf_material = 0;
    uint32_t noise_seed = 0;
};
constexpr double kTreeCoreScale = 0.6;  // the opaque core's size relative to the crown

TreeShape tree_shape(const Scene& scene, uint32_t index);
// The same from the few numbers the procedural mode keeps per tree.
TreeShape tree_shape(float x, float y, float height, float crown, bool needle, double ground_z, uint32_t index);

// Whether the crown shell has leaves at p (world metres): 3D value noise at two scales
// (0.7 m clumps, 0.25 m leaves), about 45 % cut away.
bool leaf_present(const TreeShape& tree, Vec3 p);

std::unique_ptr<RenderGeometry> build_stored_trees(const Scene& scene);
std::unique_ptr<RenderGeometry> build_procedural_trees(const Scene& scene);

}  // namespace citygen
