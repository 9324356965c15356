// Paths and rails (format 1.1): flat strips and joints just below the roads (a footway
// crossing a street disappears under it), one material per class; rail classes show their
// rails (and sleepers, but for trams) as a shading-time pattern, the same in both modes.
// Tram tracks are paved and lie just above the roads, so street tracks show their rails.
#pragma once

#include <memory>

#include "common/scene.h"
#include "render/geometry/procedural_geometry.h"
#include "render/scene/render_scene.h"
#include "render/scene/triangle_mesh.h"

namespace citygen {

constexpr double kPathLift = 0.018;  // above land cover, below kRoadLift
constexpr double kTramLift = 0.023;  // tram tracks lie in the street: just above kRoadLift

// Height of a path's strip: trams above the road they run in (paved, with rails), others below.
double path_z(const Scene& scene, const PathEdge& path);
double path_lift(const PathEdge& path);  // path_z = scene.ground.z + this; draped this far above a field

uint16_t path_material(PathClass c);
TriangleMesh build_stored_paths(const Scene& scene);
TriangleMesh build_stored_path_joints(const Scene& scene);
std::unique_ptr<ProceduralGeometry> build_procedural_paths(const Scene& scene);
std::unique_ptr<ProceduralGeometry> build_procedural_path_joints(const Scene& scene);

// What a path's surface is worked out from: its class and the ends of its centreline.
struct PathPaint {
    Vec2 a, b;
    PathClass path_class = PathClass::Footway;
    bool straight = false;  // a centreline of two points or more
};
PathPaint path_paint(const PathEdge& path);

// The material at p on a path: rails 1.435 m apart (7 cm heads) and sleepers every 0.6 m on
// rail classes, else the class material.
uint16_t path_surface_material(const PathPaint& path, Vec2 p);

// Wraps the path geometry (either mode) so rail strips show their track.
std::unique_ptr<RenderGeometry> with_rail_tracks(std::unique_ptr<RenderGeometry> geometry, const Scene& scene);

}  // namespace citygen
