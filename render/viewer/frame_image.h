// The 8-bit pictures the viewer sends: the tone-mapped image (as render's PNG output maps it),
// an AOV as a picture, and bounding boxes drawn over either.
#pragma once

#include <vector>

#include "common/scene.h"
#include "render/camera/camera.h"
#include "render/film/render_image.h"
#include "render/viewer/view_request.h"

namespace citygen {

// 3 bytes per pixel, row-major, sRGB.
std::vector<unsigned char> tone_mapped_rgb8(const Film& film, double exposure);

// A film rendered with AOVs as a picture of `layer`: albedo as a colour, normals as 0.5 + n/2,
// depth from near (white) to far (black) on a log scale, ids as a colour per object.
std::vector<unsigned char> layer_rgb8(const Film& film, ViewLayer layer);

// The boxes around buildings (base to top) and roads (half a metre high), drawn as lines on
// `rgb` (the camera's image, any size: the camera is resized to it).
void draw_boxes(const Scene& scene, const Camera& camera, bool buildings, bool roads, int width, int height,
                std::vector<unsigned char>& rgb);

}  // namespace citygen
