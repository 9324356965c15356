#include "render/facade/building_textures.h"

#include <cmath>
#include <filesystem>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/texture.h>

#include "common/error.h"

namespace citygen {

namespace {

OIIO::TextureSystem* texture_system(void* p) { return static_cast<OIIO::TextureSystem*>(p); }

double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

}  // namespace

BuildingTextures::BuildingTextures(const std::string& dir, double pixel_angle) : pixel_angle_(pixel_angle) {
    std::error_code ec;
    if (!std::filesystem::is_directory(dir, ec)) throw Error("--texture-dir: " + dir + " is not a directory");
    // The process-wide shared texture system, never destroyed by us: OpenImageIO 2.4's
    // TextureSystem::destroy deletes through the base class with a sized delete, which
    // AddressSanitizer reports as a new/delete type mismatch inside the library.
    OIIO::TextureSystem* ts = OIIO::TextureSystem::create(true);
    ts->attribute("automip", 1);  // plain PNG/JPEG tiles get their MIP levels on first use
    system_ = ts;
    for (int i = 0; i < kWallMaterialCount; ++i) walls_[i] = load(dir, to_string(static_cast<WallMaterial>(i)));
    for (int i = 0; i < kRoofMaterialCount; ++i)
        roofs_[i] = load(dir, std::string("roof_") + to_string(static_cast<RoofMaterial>(i)));
    if (count() == 0) {
        system_ = nullptr;
        throw Error("--texture-dir: " + dir + " holds no texture named after a material (e.g. brick.png, roof_slate.png)");
    }
}

BuildingTextures::~BuildingTextures() = default;  // the shared texture system lives until exit

int BuildingTextures::count() const {
    int n = 0;
    for (const Texture& t : walls_) n += t.found;
    for (const Texture& t : roofs_) n += t.found;
    return n;
}

BuildingTextures::Texture BuildingTextures::load(const std::string& dir, const std::string& name) const {
    Texture t;
    for (const char* ext : {".exr", ".tx", ".png", ".jpg", ".jpeg", ".tif"}) {
        const std::string path = dir + "/" + name + ext;
        std::error_code ec;
        if (!std::filesystem::is_regular_file(path, ec)) continue;
        OIIO::ImageBuf image(path);
        if (!image.read(0, 0, true, OIIO::TypeDesc::FLOAT) || image.nchannels() < 1)
            throw Error("--texture-dir: cannot read " + path + ": " + image.geterror());
        t.found = true;
        t.path = path;
        t.srgb = std::string(ext) != ".exr" && std::string(ext) != ".tx";
        // The mean (linear) colour, so the texture modulates the building's colour around 1.
        const int channels = std::min(3, image.nchannels());
        double sum[3] = {0, 0, 0};
        size_t pixels = 0;
        for (OIIO::ImageBuf::ConstIterator<float> it(image); !it.done(); ++it, ++pixels)
            for (int c = 0; c < 3; ++c) {
                const double value = it[std::min(c, channels - 1)];
                sum[c] += t.srgb ? srgb_to_linear(value) : value;
            }
        for (int c = 0; c < 3; ++c) {
            const double mean = pixels ? sum[c] / pixels : 0;
            (c == 0 ? t.inverse_mean.x : c == 1 ? t.inverse_mean.y : t.inverse_mean.z) = mean > 1e-4 ? 1 / mean : 0;
        }
        return t;
    }
    return t;
}

Color BuildingTextures::lookup(const Texture& t, double u, double v, double distance) const {
    OIIO::TextureOpt options;
    options.swrap = options.twrap = OIIO::TextureOpt::WrapPeriodic;
    // Texture space: one unit per repeat; the pixel's footprint there sets the MIP level.
    const float s = static_cast<float>(u / kTextureRepeat), tt = static_cast<float>(-v / kTextureRepeat);
    const float width = static_cast<float>(distance * pixel_angle_ / kTextureRepeat);
    float rgb[3] = {1, 1, 1};
    if (!texture_system(system_)->texture(OIIO::ustring(t.path), options, s - std::floor(s), tt - std::floor(tt),
                                          width, 0, 0, width, 3, rgb))
        return {1, 1, 1};
    Color c{rgb[0], rgb[1], rgb[2]};
    if (t.srgb) c = {srgb_to_linear(c.x), srgb_to_linear(c.y), srgb_to_linear(c.z)};
    return c * t.inverse_mean;
}

Color BuildingTextures::factor(WallMaterial m, double u, double v, double distance) const {
    return lookup(walls_[static_cast<int>(m)], u, v, distance);
}

Color BuildingTextures::factor(RoofMaterial m, double u, double v, double distance) const {
    return lookup(roofs_[static_cast<int>(m)], u, v, distance);
}

}  // namespace citygen
