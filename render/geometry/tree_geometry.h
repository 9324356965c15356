// Trees (format 1.1) in both geometry modes: a trunk (an 8-sided prism) and a crown (a faceted
// ellipsoid shell with a noise cut-out at leaf-clump scale, around an opaque faceted inner core),
// so light falls through in patches and the crown shows leaf-scale detail.
// The shape is defined once: the trunk's and the crown's vertices (trunk_vertex, crown_vertex)
// and the cut-out (leaf_at). Every part is a convex polyhedron (the prism without caps, the two
// shells closed), so
//   - stored: triangulates those facets; an Embree filter function cuts the shell where the
//     leaf noise says "gap";
//   - procedural: one user primitive per tree, 20 bytes of our own; the callback clips the ray
//     against the same facets' planes (the crown's from one shared unit tessellation scaled by
//     the tree's semi-axes) and applies the same cut-out at the hit point.
// So both modes hit the same surfaces (to float precision) and cut the same gaps.
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
constexpr int kTrunkSides = 8;

// How finely a crown shell is faceted: `segments` around the axis, `rings` from pole to pole.
struct CrownFacets {
    int segments, rings;
};
constexpr CrownFacets kShellFacets{16, 10}, kCoreFacets{8, 5};

// Vertex j of the trunk's foot (counter-clockwise, kTrunkSides around); its top is trunk_top above.
Vec3 trunk_vertex(const TreeShape& tree, int j);
// Vertex (ring k from the top, 0..rings; segment j, 0..segments-1) of the shell with centre c and
// semi-axes (r, r, h): on a slightly larger ellipsoid, so the facets straddle the true surface.
Vec3 crown_vertex(Vec3 c, double r, double h, CrownFacets facets, int k, int j);

TreeShape tree_shape(const Scene& scene, uint32_t index);
// The same from the few numbers the procedural mode keeps per tree.
TreeShape tree_shape(float x, float y, float height, float crown, bool needle, double ground_z);

// Whether the crown shell has leaves at p (world metres): 3D value noise at two scales
// (0.7 m clumps, 0.25 m leaves), about 45 % cut away.
bool leaf_present(const TreeShape& tree, Vec3 p);
// The cut-out at a hit p on the crown shell: the leaf noise at p moved radially onto the
// crown's ellipsoid (what both modes evaluate at their hit).
bool leaf_at(const TreeShape& tree, Vec3 p);

std::unique_ptr<RenderGeometry> build_stored_trees(const Scene& scene);
std::unique_ptr<RenderGeometry> build_procedural_trees(const Scene& scene);

}  // namespace citygen
