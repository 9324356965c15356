// Rendering a whole image: tiles in parallel (TBB), one random stream per pixel so the result
// does not depend on the thread count, optional AOVs from the ray through each pixel centre.
#pragma once

#include <cstdint>
#include <vector>

#include "camera.h"
#include "integrator.h"

namespace citygen {

struct RenderSettings {
    int width = 1280, height = 720;
    int spp = 16;
    uint64_t seed = 1;
    IntegratorSettings integrator;
    bool aovs = false;   // fill depth, normal, albedo and id
    bool quiet = false;  // no progress bar
};

// Linear float images, row-major from the top-left pixel.
struct Film {
    int width = 0, height = 0;
    std::vector<float> rgb;          // 3 per pixel, radiance (before exposure)
    // AOVs, present when RenderSettings::aovs: from the primary ray through the pixel centre.
    std::vector<float> depth;        // metres along the ray; 0 where the ray escapes
    std::vector<float> normal;       // 3 per pixel, facing the camera
    std::vector<float> albedo;       // 3 per pixel
    std::vector<float> object_kind;  // ObjectKind as a number (0: sky)
    std::vector<float> object_index; // index of the object in the scene file's list of its kind
};

struct RenderStats {
    double seconds = 0;
    uint64_t rays = 0;
};

Film render_image(const PathContext& context, const Camera& camera, const RenderSettings& settings,
                  RenderStats* stats = nullptr);

}  // namespace citygen
