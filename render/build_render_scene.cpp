#include "build_render_scene.h"

#include <string>

#include "error.h"
#include "stored_geometry.h"

namespace citygen {

namespace {

using StoredBuilder = TriangleMesh (*)(const Scene&);

std::unique_ptr<RenderGeometry> build_class(const Scene& scene, GeometryClass c, GeometryMode mode,
                                            StoredBuilder stored) {
    if (mode == GeometryMode::Stored) return std::make_unique<StoredMeshGeometry>(stored(scene));
    throw Error(std::string("--geometry-") + to_string(c) + "=procedural: the procedural mode is not built yet");
}

}  // namespace

std::unique_ptr<RenderScene> build_render_scene(const Scene& scene, const GeometryModes& modes) {
    auto render_scene = std::make_unique<RenderScene>();
    render_scene->add(
        build_class(scene, GeometryClass::Buildings, modes[GeometryClass::Buildings], build_stored_buildings));
    render_scene->add(build_class(scene, GeometryClass::Terrain, modes[GeometryClass::Terrain], build_stored_terrain));
    render_scene->add(build_class(scene, GeometryClass::Roads, modes[GeometryClass::Roads], build_stored_roads));
    render_scene->add(build_class(scene, GeometryClass::Joints, modes[GeometryClass::Joints], build_stored_joints));
    render_scene->add(
        build_class(scene, GeometryClass::Sidewalks, modes[GeometryClass::Sidewalks], build_stored_sidewalks));
    render_scene->commit();
    return render_scene;
}

}  // namespace citygen
