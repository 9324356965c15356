// Parsers for render's option values that CLI11 cannot check by itself. Each throws
// citygen::Error with one line naming the option; fuzzed by tests/fuzz/cli_values_fuzz.cpp.
#pragma once

#include <string>

#include "common/geometry.h"
#include "render/film/render_image.h"

namespace citygen {

// "X,Y,Z" in scene metres, each finite and within kMaxCoordinate (scene_limits.h) of the origin.
Vec3 parse_point(const std::string& text, const std::string& option);

// Refuses a camera that sits on the point it looks at (no direction to look in).
void check_view(Vec3 camera, Vec3 look_at);

// --region "X0,Y0,X1,Y1" in pixels, a non-empty rectangle (render_region checks it lies in the frame).
PixelRegion parse_region(const std::string& text);

}  // namespace citygen
