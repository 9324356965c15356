#include "render/facade/facade_materials.h"

#include "render/materials/materials.h"

namespace citygen {

std::array<uint16_t, kFacadeSurfaceCount> facade_surface_materials() {
    std::array<uint16_t, kFacadeSurfaceCount> m{};
    m[static_cast<int>(FacadeSurface::Wall)] = kFacade;
    m[static_cast<int>(FacadeSurface::Reveal)] = kFacade;
    m[static_cast<int>(FacadeSurface::Glass)] = kGlass;
    m[static_cast<int>(FacadeSurface::Room)] = kRoomInterior;
    m[static_cast<int>(FacadeSurface::BalconySlab)] = kBalcony;
    m[static_cast<int>(FacadeSurface::Fence)] = kFence;
    m[static_cast<int>(FacadeSurface::BalconyDoor)] = kGlass;
    m[static_cast<int>(FacadeSurface::ShopWindow)] = kShopWindow;
    return m;
}

}  // namespace citygen
