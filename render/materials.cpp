#include "materials.h"

namespace citygen {

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
    t[kLampPole] = {"lamp_pole", MaterialType::Glossy, {0.04, 0.045, 0.05}, {0.15, 0.15, 0.15}, 30, 1.5, {}};
    t[kLampGlobe] = {"lamp_globe", MaterialType::Diffuse, {0.8, 0.8, 0.8}, {}, 1, 1.5, {}};
    t[kLampCap] = {"lamp_cap", MaterialType::Glossy, {0.04, 0.045, 0.05}, {0.15, 0.15, 0.15}, 30, 1.5, {}};
    return t;
}

}  // namespace citygen
