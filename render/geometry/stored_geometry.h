// Stored-mode builders: one function per object class, each turning the scene's objects into
// a triangle mesh whose faces remember (object index, material).
#pragma once

#include <array>
#include <vector>

#include "common/progress.h"
#include "common/scene.h"
#include "render/facade/facade.h"
#include "render/scene/triangle_mesh.h"

namespace citygen {

// Heights of the flat layers above the ground plane, so coplanar surfaces never fight.
constexpr double kRoadLift = 0.02;

// Walls from every ring (holes included) from min_height to height, carrying the facade rules
// (windows, balconies, shop fronts; render/facade/facade.h) as triangles, flat roof triangulated with
// holes, and a floor when the building floats (min_height > 0).
// `progress` (optional) advances once per building.
TriangleMesh build_stored_buildings(const Scene& scene, const FacadeOptions& facades, Progress* progress = nullptr);

// Road quadrangles and joint polygons, flat just above the ground.
TriangleMesh build_stored_roads(const Scene& scene);
TriangleMesh build_stored_joints(const Scene& scene);

// Sidewalk tops raised by their curb height, with vertical curb faces around each piece.
TriangleMesh build_stored_sidewalks(const Scene& scene);

// The ground plane: the scene's ground extent plus a wide margin, so the default view never
// looks past its edge.
TriangleMesh build_stored_terrain(const Scene& scene);

// Street lamps (lamp_shape.h): pole, glowing globe and cap as triangles.
TriangleMesh build_stored_lamps(const Scene& scene);

// A sidewalk piece as both geometry modes build it: its ring counter-clockwise, the road
// level and the curb top. False for a degenerate piece (fewer than 3 points).
struct SidewalkShape {
    Ring ring;
    double road_z = 0, top_z = 0;
    bool has_curb() const { return top_z > road_z; }
};
bool sidewalk_shape(const Scene& scene, uint32_t index, SidewalkShape* shape);
// On a field: the curb faces of a sidewalk piece, each vertical quad (foot a, foot b, top b,
// top a) facing out, over the ring split_at_field_lines, so each foot follows the drawn ground.
using CurbFace = std::array<Vec3, 4>;
std::vector<CurbFace> draped_curb_faces(const Scene& scene, const SidewalkShape& shape);

// A roof face's points standing on the ground at ground_z (the scene's faces stand on z = 0),
// and its material: roof faces kRoof, gable walls kFacade. Shared by both geometry modes.
std::vector<Vec3> lifted_face(const RoofFace& face, double ground_z);
uint16_t roof_face_material(const RoofFace& face);

// A flat polygon at height z as triangles, front side up (roads, joints, sidewalk tops, paths).
void add_flat_polygon(const Ring& ring, double z, uint32_t object, uint16_t material, TriangleMesh& mesh);

// A flat polygon `lift` above the ground: at scene.ground.z + lift without a field (as
// add_flat_polygon), draped over the field (ground.h's drape_polygon) with one.
void add_ground_polygon(const Scene& scene, const Ring& outer, const std::vector<Ring>& holes, double lift,
                        uint32_t object, uint16_t material, TriangleMesh& mesh);

// The rectangle build_stored_terrain covers (shared with the procedural terrain).
Box2 terrain_extent(const Scene& scene);

}  // namespace citygen
