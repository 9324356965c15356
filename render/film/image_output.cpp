#include "render/film/image_output.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <cerrno>
#include <memory>
#include <unistd.h>

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include "common/error.h"
#include "common/scene_io.h"

namespace citygen {

namespace {

std::string lower_extension(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    const size_t dot = path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash)) return "";
    std::string ext = path.substr(dot + 1);
    for (char& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    return ext;
}

float srgb_encode(float v) {
    v = std::clamp(v, 0.f, 1.f);
    return v <= 0.0031308f ? 12.92f * v : 1.055f * std::pow(v, 1 / 2.4f) - 0.055f;
}

}  // namespace

ImageFormat image_format_for(const std::string& path) {
    const std::string ext = lower_extension(path);
    if (ext == "png") return ImageFormat::Png;
    if (ext == "jpg" || ext == "jpeg") return ImageFormat::Jpeg;
    if (ext == "exr") return ImageFormat::Exr;
    throw Error(path + ": unknown image extension (use .png, .jpg or .exr)");
}

float tone_map(float linear, double exposure) {
    // Filmic curve (Narkowicz's fit of the ACES reference rendering): a toe that keeps shadows
    // rich and a shoulder that rolls highlights (lamps, lit windows, the sun) off to white
    // instead of clipping them.
    const double x = std::max(0.0, static_cast<double>(linear) * exposure);
    const double y = x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14);
    return srgb_encode(static_cast<float>(y));
}

namespace {

const char* name_for(ImageFormat format) {
    return format == ImageFormat::Png ? "image.png" : format == ImageFormat::Jpeg ? "image.jpg" : "image.exr";
}

// Encodes `data` (of `type`, laid out as `spec` says) in memory; throws citygen::Error.
std::vector<unsigned char> encode(const OIIO::ImageSpec& spec, OIIO::TypeDesc type, const void* data,
                                  ImageFormat format) {
    using namespace OIIO;
    // The image libraries do not all report a full disk (libpng did not), and libjpeg prints its
    // own line, so encoding goes to memory and write_file_atomically checks every write.
    std::vector<unsigned char> bytes;
    Filesystem::IOVecOutput memory(bytes);
    const std::string name = name_for(format);
    auto out = ImageOutput::create(name);
    bool ok = out && out->supports("ioproxy") && out->set_ioproxy(&memory) && out->open(name, spec) &&
              out->write_image(type, data);
    std::string reason = out ? out->geterror() : OIIO::geterror();
    if (out) ok = out->close() && ok;
    if (!ok) {
        if (reason.empty()) reason = "encoding failed";
        throw Error("cannot encode image (" + reason.substr(0, reason.find('\n')) + ")");
    }
    return bytes;
}

}  // namespace

std::vector<unsigned char> encode_image(const Film& film, ImageFormat format, double exposure) {
    using namespace OIIO;
    const size_t pixels = static_cast<size_t>(film.width) * film.height;

    std::vector<float> data;
    ImageSpec spec;
    if (format == ImageFormat::Exr) {
        std::vector<std::string> names{"R", "G", "B"};
        const bool aovs = !film.depth.empty();
        if (aovs)
            names.insert(names.end(), {"Z", "N.X", "N.Y", "N.Z", "albedo.R", "albedo.G", "albedo.B", "id.kind",
                                       "id.index"});
        // A denoised film keeps its unfiltered radiance as a layer of its own.
        const bool raw = !film.raw_rgb.empty();
        const int raw_channel = static_cast<int>(names.size());
        if (raw) names.insert(names.end(), {"raw.R", "raw.G", "raw.B"});
        const int channels = static_cast<int>(names.size());
        spec = ImageSpec(film.width, film.height, channels, TypeDesc::FLOAT);
        spec.channelnames = names;
        spec.z_channel = aovs ? 3 : -1;
        spec.attribute("compression", "zip");
        data.resize(pixels * channels);
        for (size_t i = 0; i < pixels; ++i) {
            float* p = &data[i * channels];
            for (int c = 0; c < 3; ++c) p[c] = film.rgb[3 * i + c];  // linear and unscaled
            if (raw)
                for (int c = 0; c < 3; ++c) p[raw_channel + c] = film.raw_rgb[3 * i + c];
            if (!aovs) continue;
            p[3] = film.depth[i];
            for (int c = 0; c < 3; ++c) p[4 + c] = film.normal[3 * i + c];
            for (int c = 0; c < 3; ++c) p[7 + c] = film.albedo[3 * i + c];
            p[10] = film.object_kind[i];
            p[11] = film.object_index[i];
        }
    } else {
        spec = ImageSpec(film.width, film.height, 3, TypeDesc::UINT8);
        if (format == ImageFormat::Jpeg) spec.attribute("Compression", "jpeg:92");
        data.resize(pixels * 3);
        for (size_t i = 0; i < 3 * pixels; ++i) data[i] = tone_map(film.rgb[i], exposure);
    }

    // Same scene, options and seed must give the same bytes: OpenImageIO stamps EXR files with the
    // write time unless DateTime is set, and it leaves out an empty one.
    spec.attribute("DateTime", "");

    return encode(spec, TypeDesc::FLOAT, data.data(), format);
}

std::vector<unsigned char> encode_rgb8(int width, int height, const std::vector<unsigned char>& rgb,
                                       ImageFormat format, int jpeg_quality) {
    using namespace OIIO;
    ImageSpec spec(width, height, 3, TypeDesc::UINT8);
    if (format == ImageFormat::Jpeg) spec.attribute("Compression", "jpeg:" + std::to_string(jpeg_quality));
    spec.attribute("DateTime", "");
    return encode(spec, TypeDesc::UINT8, rgb.data(), format);
}

void write_image(const Film& film, const std::string& path, double exposure) {
    std::vector<unsigned char> bytes;
    try {
        bytes = encode_image(film, image_format_for(path), exposure);
    } catch (const Error& e) {
        throw Error(path + ": " + e.what());
    }
    write_file_atomically(path, bytes.data(), bytes.size());
}

}  // namespace citygen
