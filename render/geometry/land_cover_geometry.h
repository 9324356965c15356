// Land cover (format 1.1): flat polygons with holes, one material per class, each class at
// its own small height above the ground (land_cover_priority), below the roads. Water and
// sea get small procedural waves as a shading-normal perturbation.
#pragma once

#include <memory>

#include "common/scene.h"
#include "render/geometry/procedural_geometry.h"
#include "render/scene/render_scene.h"
#include "render/scene/triangle_mesh.h"

namespace citygen {

// Height of a class's surface above the ground: 2 mm steps by priority, all below kRoadLift.
double land_cover_z(const Scene& scene, LandCoverClass c);
// Its height above the ground (land_cover_z = scene.ground.z + this); on a field every class but
// the sea is draped this far above the ground, the sea stays at land_cover_z.
double land_cover_lift(LandCoverClass c);
uint16_t land_cover_material(LandCoverClass c);

// Stored: each polygon triangulated (holes kept).
TriangleMesh build_stored_land_cover(const Scene& scene);
// Procedural: each polygon cut into grid tiles of a few dozen vertices (a sea polygon has
// thousands), one primitive per tile: plane hit + point-in-polygon on the tile's rings.
std::unique_ptr<ProceduralGeometry> build_procedural_land_cover(const Scene& scene);

// The slope of the water surface at p (metres): a few long-crested wave trains, stronger
// on the sea than on lakes. Returns the shading normal.
Vec3 water_normal(Vec2 p, bool sea);

// Wraps land cover geometry of either mode so water hits get their wave normals.
std::unique_ptr<RenderGeometry> with_water_waves(std::unique_ptr<RenderGeometry> geometry);

}  // namespace citygen
