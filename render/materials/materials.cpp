#include "render/materials/materials.h"

namespace citygen {

namespace {
constexpr double kSeaExponent = 200, kInlandWaterExponent = 600;
}  // namespace

MaterialTable default_materials() {
    MaterialTable t(kStockMaterialCount);
    // Albedos are rough measured values of the real surfaces (asphalt ~0.08, concrete ~0.35).
    t[kAsphalt] = {"asphalt", MaterialType::Glossy, {0.07, 0.07, 0.075}, {0.04, 0.04, 0.04}, 40, 1.5, {}};
    t[kSidewalk] = {"sidewalk", MaterialType::Diffuse, {0.38, 0.37, 0.35}, {}, 1, 1.5, {}};
    t[kCurb] = {"curb", MaterialType::Diffuse, {0.5, 0.5, 0.48}, {}, 1, 1.5, {}};
    t[kFacade] = {"facade", MaterialType::Diffuse, {0.62, 0.55, 0.45}, {}, 1, 1.5, {}};
    t[kRoof] = {"roof", MaterialType::Glossy, {0.42, 0.2, 0.14}, {0.03, 0.03, 0.03}, 20, 1.5, {}};
    t[kGround] = {"ground", MaterialType::Diffuse, {0.2, 0.24, 0.15}, {}, 1, 1.5, {}};
    t[kGlass] = {"glass", MaterialType::Glass, {0, 0, 0}, {1, 1, 1}, 1, 1.5, {}};
    t[kMirror] = {"mirror", MaterialType::Mirror, {0, 0, 0}, {1, 1, 1}, 1, 1.5, {}};
    t[kRoomInterior] = {"room_interior", MaterialType::Diffuse, {0.55, 0.45, 0.35}, {}, 1, 1.5, {}};
    t[kBalcony] = {"balcony", MaterialType::Diffuse, {0.5, 0.5, 0.48}, {}, 1, 1.5, {}};
    t[kFence] = {"fence", MaterialType::Glossy, {0.05, 0.05, 0.06}, {0.2, 0.2, 0.2}, 60, 1.5, {}};
    t[kShopWindow] = {"shop_window", MaterialType::Glass, {0, 0, 0}, {0.95, 0.97, 1.0}, 1, 1.5, {}};
    // Water: the wave normals (land_cover_geometry.cpp) model waves of metres; the lobe is the
    // ripples below that, wider on the open sea than on sheltered inland water.
    t[kWater] = {"water", MaterialType::Water, {0.025, 0.05, 0.045}, {1, 1, 1}, kInlandWaterExponent, 1.33, {}};
    t[kSea] = {"sea", MaterialType::Water, {0.01, 0.035, 0.06}, {1, 1, 1}, kSeaExponent, 1.33, {}};
    t[kGrass] = {"grass", MaterialType::Diffuse, {0.1, 0.2, 0.05}, {}, 1, 1.5, {}};
    t[kForestFloor] = {"forest_floor", MaterialType::Diffuse, {0.07, 0.1, 0.04}, {}, 1, 1.5, {}};
    t[kPaving] = {"paving", MaterialType::Diffuse, {0.32, 0.3, 0.27}, {}, 1, 1.5, {}};
    t[kSand] = {"sand", MaterialType::Diffuse, {0.55, 0.47, 0.33}, {}, 1, 1.5, {}};
    t[kFarmland] = {"farmland", MaterialType::Diffuse, {0.26, 0.22, 0.11}, {}, 1, 1.5, {}};
    t[kUrbanGround] = {"urban_ground", MaterialType::Diffuse, {0.21, 0.2, 0.19}, {}, 1, 1.5, {}};
    t[kBark] = {"bark", MaterialType::Diffuse, {0.11, 0.08, 0.05}, {}, 1, 1.5, {}};
    t[kLeavesBroad] = {"leaves_broad", MaterialType::Diffuse, {0.07, 0.15, 0.035}, {}, 1, 1.5, {}};
    t[kLeavesNeedle] = {"leaves_needle", MaterialType::Diffuse, {0.035, 0.085, 0.04}, {}, 1, 1.5, {}};
    // Road paint: brighter than asphalt and a little smoother.
    t[kPaintWhite] = {"paint_white", MaterialType::Glossy, {0.7, 0.7, 0.68}, {0.05, 0.05, 0.05}, 60, 1.5, {}};
    t[kPathPaving] = {"path_paving", MaterialType::Diffuse, {0.42, 0.39, 0.35}, {}, 1, 1.5, {}};
    t[kCyclewaySurface] = {"cycleway", MaterialType::Diffuse, {0.28, 0.11, 0.09}, {}, 1, 1.5, {}};
    t[kGravel] = {"gravel", MaterialType::Diffuse, {0.36, 0.31, 0.24}, {}, 1, 1.5, {}};
    t[kBallast] = {"ballast", MaterialType::Diffuse, {0.2, 0.19, 0.18}, {}, 1, 1.5, {}};
    t[kRailSteel] = {"rail_steel", MaterialType::Glossy, {0.25, 0.24, 0.23}, {0.3, 0.3, 0.3}, 80, 1.5, {}};
    t[kSleeper] = {"sleeper", MaterialType::Diffuse, {0.38, 0.37, 0.35}, {}, 1, 1.5, {}};
    t[kAsphaltLight] = {"asphalt_light", MaterialType::Glossy, {0.11, 0.11, 0.115}, {0.04, 0.04, 0.04}, 40, 1.5, {}};
    t[kLampPole] = {"lamp_pole", MaterialType::Glossy, {0.04, 0.045, 0.05}, {0.15, 0.15, 0.15}, 30, 1.5, {}};
    t[kLampGlobe] = {"lamp_globe", MaterialType::Diffuse, {0.8, 0.8, 0.8}, {}, 1, 1.5, {}};
    t[kLampCap] = {"lamp_cap", MaterialType::Glossy, {0.04, 0.045, 0.05}, {0.15, 0.15, 0.15}, 30, 1.5, {}};
    // Weathered retaining walls: grey concrete, a warm limestone (Monaco's walls), brick, timber.
    t[kRetainingConcrete] = {"retaining_concrete", MaterialType::Diffuse, {0.33, 0.33, 0.31}, {}, 1, 1.5, {}};
    t[kRetainingStone] = {"retaining_stone", MaterialType::Diffuse, {0.42, 0.38, 0.31}, {}, 1, 1.5, {}};
    t[kRetainingBrick] = {"retaining_brick", MaterialType::Diffuse, {0.33, 0.16, 0.11}, {}, 1, 1.5, {}};
    t[kRetainingWood] = {"retaining_wood", MaterialType::Diffuse, {0.2, 0.14, 0.09}, {}, 1, 1.5, {}};
    return t;
}

}  // namespace citygen
