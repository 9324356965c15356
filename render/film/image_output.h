// Writing the film through OpenImageIO, chosen by the file extension: PNG/JPEG tone-mapped to
// 8-bit sRGB, EXR linear half/float with optional AOV channels. Always atomic.
#pragma once

#include <string>
#include <vector>

#include "render/film/render_image.h"

namespace citygen {

enum class ImageFormat { Png, Jpeg, Exr };

// Throws citygen::Error for an extension we cannot write.
ImageFormat image_format_for(const std::string& path);

// Exposure-scaled, tone-mapped (filmic curve) and sRGB-encoded value in [0, 1].
float tone_map(float linear, double exposure);

// The file's bytes, encoded in memory as write_image writes them; throws citygen::Error.
std::vector<unsigned char> encode_image(const Film& film, ImageFormat format, double exposure);
// An 8-bit sRGB image (3 bytes per pixel, row-major) as PNG or JPEG (the viewer's frames).
std::vector<unsigned char> encode_rgb8(int width, int height, const std::vector<unsigned char>& rgb,
                                       ImageFormat format, int jpeg_quality = 85);

// Encodes in memory, writes to a temporary name beside `path`, then renames it over `path`.
// EXR gets R,G,B (radiance, linear, not scaled by the exposure) plus, when the film has them, the AOV
// channels Z, N.X/N.Y/N.Z, albedo.R/G/B, id.kind, id.index, and raw.R/G/B when the film was denoised.
void write_image(const Film& film, const std::string& path, double exposure);

}  // namespace citygen
