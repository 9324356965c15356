// Optional user tile textures for building walls and roofs (--texture-dir), looked up through
// OpenImageIO's TextureSystem (MIP-mapped, filtered by the pixel's footprint). A texture
// replaces the procedural pattern of its material (building_looks.h) in the same wall or roof
// coordinates, one repeat every kTextureRepeat metres; like the patterns it modulates the
// building's own colour: the albedo is the colour times the texture divided by its mean, so a
// brick photo keeps its detail and takes the colour the map gives.
#pragma once

#include <array>
#include <string>

#include "common/scene.h"
#include "render/materials/materials.h"

namespace citygen {

constexpr double kTextureRepeat = 2.0;  // metres per texture tile, along and up

class BuildingTextures {
public:
    // Finds DIR/<material>.{exr,tx,png,jpg,jpeg,tif} for each wall material (plaster, brick,
    // concrete, stone, glass, wood, metal) and roof material (roof_tiles, slate, metal, copper,
    // concrete, tar_paper, thatch, glass, grass; a roof file is named roof_<material>, e.g.
    // roof_slate.png). Throws citygen::Error when DIR is not a directory, holds none of these, or
    // a file cannot be read. `pixel_angle`: radians per pixel, for the filter footprint.
    BuildingTextures(const std::string& dir, double pixel_angle);
    ~BuildingTextures();
    BuildingTextures(const BuildingTextures&) = delete;
    BuildingTextures& operator=(const BuildingTextures&) = delete;

    int count() const;  // textures found
    bool has(WallMaterial m) const { return walls_[static_cast<int>(m)].found; }
    bool has(RoofMaterial m) const { return roofs_[static_cast<int>(m)].found; }
    // The modulation factor (about 1 on average) at (u, v) metres seen from `distance` metres.
    Color factor(WallMaterial m, double u, double v, double distance) const;
    Color factor(RoofMaterial m, double u, double v, double distance) const;

private:
    struct Texture {
        bool found = false;
        bool srgb = true;       // 8-bit formats are sRGB; EXR and TX are linear
        std::string path;
        Color inverse_mean{1, 1, 1};
    };
    Texture load(const std::string& dir, const std::string& name) const;
    Color lookup(const Texture& t, double u, double v, double distance) const;

    void* system_ = nullptr;  // OIIO::TextureSystem (kept out of this header)
    double pixel_angle_ = 0;
    std::array<Texture, kWallMaterialCount> walls_;
    std::array<Texture, kRoofMaterialCount> roofs_;
};

}  // namespace citygen
