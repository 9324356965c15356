// Each building's own colours and materials (scene format 1.1), and the procedural tile
// patterns on its walls and roof: brick courses, plaster grain, concrete panels, stone blocks,
// wooden boards, corrugated metal; roof tiles, slates, metal seams. Patterns are functions of
// the hit position in wall or roof coordinates (u along the wall or eaves, v up the wall or
// slope), so both geometry modes show the same thing without any stored texture coordinates.
#pragma once

#include <vector>

#include "common/scene.h"
#include "render/facade/building_textures.h"
#include "render/materials/materials.h"
#include "render/scene/hit.h"

namespace citygen {

class CellUnits;  // the pattern's noise cells last hashed (building_looks.cpp)

class BuildingLooks {
public:
    BuildingLooks() = default;
    explicit BuildingLooks(const Scene& scene);

    // The material a hit is shaded with: the stock one, except on a building's walls (kFacade)
    // and roof (kRoof), which get that building's colour (linear), modulated by its pattern;
    // there it also tilts hit.shading_normal by the relief of the pattern (same coordinates).
    Material bumped_material(const MaterialTable& table, Hit& hit) const;
    // User tile textures (--texture-dir) that replace the patterns of their materials; null: none.
    void use_textures(const BuildingTextures* textures) { textures_ = textures; }

private:
    void bump(Hit& hit, CellUnits& cells) const;
    Material material_for(const MaterialTable& table, const Hit& hit, CellUnits& cells) const;
    // Colours as the scene keeps them (a metropolis has a million buildings), made linear when shaded.
    struct Look {
        uint32_t wall_colour, roof_colour;  // sRGB 0xFFRRGGBB, 0: none
        WallMaterial wall_material;
        RoofMaterial roof_material;
        bool has_wall() const { return wall_colour != 0; }
        bool has_roof() const { return roof_colour != 0; }
    };
    std::vector<Look> looks_;
    const BuildingTextures* textures_ = nullptr;
};

// The material a hit is shaded with (looks may be null: stock materials only); on a building's
// patterned walls and roof also tilts hit.shading_normal by the pattern's relief (bump mapping:
// mortar joints, tile rows and plaster grain catch the grazing sun).
inline Material surface_material(const MaterialTable& table, const BuildingLooks* looks, Hit& hit) {
    if (!looks) return table[hit.material];
    return looks->bumped_material(table, hit);
}

// sRGB 0xRRGGBB -> linear albedo, scaled so white paint reflects about 80%.
Color albedo_from_srgb(uint32_t rgb);

// The pattern factors (about 1) at a point, exposed for tests.
double wall_pattern(WallMaterial material, double u, double v);
double roof_pattern(RoofMaterial material, double u, double v);

}  // namespace citygen
