// Every material the renderer uses, in one table indexed by MaterialId. Geometry stores only ids;
// the integrator looks the parameters up here.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "common/geometry.h"

namespace citygen {

using Color = Vec3;  // linear RGB

enum class MaterialType : uint8_t {
    Diffuse,  // Lambertian with `albedo`
    Glossy,   // Lambertian `albedo` plus a normalised Phong lobe `specular` with `exponent`
    Mirror,   // perfect reflection scaled by `specular`
    Glass,    // smooth dielectric with index `ior`, Schlick Fresnel, tinted by `specular`
    Water,    // a rippled surface over a dark body: a Phong lobe of sharpness `exponent` around the
              // mirror direction, weighted by Schlick Fresnel (index `ior`) and tinted by
              // `specular`, else Lambertian `albedo` (the water's colour seen from above)
};

struct Material {
    std::string name;
    MaterialType type = MaterialType::Diffuse;
    Color albedo{0.5, 0.5, 0.5};
    Color specular{0, 0, 0};
    double exponent = 1;
    double ior = 1.5;
    Color emission{0, 0, 0};  // radiance leaving the surface (lit windows, bulbs later)
};

// Ids of the stock materials. New classes of surface (facade detail, lamps) append here and in
// default_materials(); the PLY export writes these numbers as the per-face material index.
enum MaterialId : uint16_t {
    kAsphalt = 0,
    kSidewalk,
    kCurb,
    kFacade,
    kRoof,
    kGround,
    kGlass,
    kMirror,
    // Facade detail (render/facade/facade.h; the mapping is render/facade/facade_materials.cpp).
    kRoomInterior,
    kBalcony,
    kFence,
    kShopWindow,
    // Land cover (one per LandCoverClass), trees and paint (the map's content, format 1.1).
    kWater,
    kSea,
    kGrass,
    kForestFloor,
    kPaving,
    kSand,
    kFarmland,
    kUrbanGround,
    kBark,
    kLeavesBroad,
    kLeavesNeedle,
    kPaintWhite,
    kPathPaving,
    kCyclewaySurface,
    kGravel,
    kBallast,
    kRailSteel,
    kSleeper,
    kAsphaltLight,  // asphalt grain: a lighter speckle of the same asphalt
    // Street lamps (lamp_shape.h); the globe's emission is set from --lamp-power/--lamp-kelvin.
    kLampPole,
    kLampGlobe,
    kLampCap,
    // Retaining walls (render/geometry/wall_geometry.h), by their material tag.
    kRetainingConcrete,
    kRetainingStone,
    kRetainingBrick,
    kRetainingWood,
    kStockMaterialCount
};

using MaterialTable = std::vector<Material>;

// The stock table, indexed by MaterialId.
MaterialTable default_materials();

}  // namespace citygen
