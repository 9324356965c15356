// Fuzzes the scene loader and what the renderer does with a loaded scene before Embree:
// decode_scene must refuse (citygen::Error) or return a scene whose buildings triangulate,
// get facades, a memory estimate, stored meshes (when small) and an automatic camera.
#include <cstdint>

#include "common/error.h"
#include "common/scene_io.h"
#include "render/camera/camera.h"
#include "render/facade/facade.h"
#include "render/geometry/stored_geometry.h"
#include "render/geometry/triangulate_polygon.h"
#include "render/production/memory_estimate.h"

using namespace citygen;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    Scene scene;
    try {
        scene = decode_scene(data, size, "fuzz.scene");
    } catch (const Error&) {
        return 0;
    }
    FacadeOptions facades;
    facades.seed = scene.header.seed;
    RenderSettings settings;
    settings.width = 64;
    settings.height = 36;
    const MemoryEstimate estimate =
        estimate_render_memory(scene, GeometryModes::all(GeometryMode::Stored), facades, settings);
    for (const Building& b : scene.buildings) triangulate_polygon(b.outer, b.holes);
    if (estimate.stored_triangles < 200000) {  // what render would build, when it is small
        build_stored_buildings(scene, facades, nullptr);
        build_stored_roads(scene);
        build_stored_joints(scene);
        build_stored_sidewalks(scene);
    }
    framing_camera(scene, 50, settings.width, settings.height);
    return 0;
}
