// How render draws a building's looks: wall and roof colours, brick courses with their bump, and
// nothing of it on other objects.
#include <gtest/gtest.h>

#include <algorithm>

#include "render/facade/building_looks.h"
#include "render/materials/materials.h"

using namespace citygen;

TEST(BuildingLooksRender, ColoursPatternsAndBumpOnlyOnBuildingWallsAndRoofs) {
    Scene scene;
    Building b;
    b.outer = {{0, 0}, {10, 0}, {10, 8}, {0, 8}};
    b.height = 9;
    b.wall_colour = 0xffcc8844;
    b.roof_colour = 0xff2f4f4f;
    b.wall_material = WallMaterial::Brick;
    b.roof_material = RoofMaterial::RoofTiles;
    scene.buildings.push_back(b);
    const BuildingLooks looks(scene);
    const MaterialTable table = default_materials();

    Hit wall;
    wall.kind = ObjectKind::Building;
    wall.material = kFacade;
    wall.geometric_normal = wall.shading_normal = {0, -1, 0};
    // Brick courses are 7.5 cm: a joint at v = 0.075 k, brick faces in between.
    double lowest = 1e9, highest = 0;
    int tilted = 0;
    for (int i = 0; i < 200; ++i) {
        wall.position = {1 + 0.0137 * i, 0, 2 + 0.0041 * i};
        wall.shading_normal = wall.geometric_normal;
        const Material m = surface_material(table, &looks, wall);
        lowest = std::min(lowest, m.albedo.x);
        highest = std::max(highest, m.albedo.x);
        tilted += dot(wall.shading_normal, wall.geometric_normal) < 0.99999;
        EXPECT_GT(dot(wall.shading_normal, wall.geometric_normal), 0.5);
    }
    EXPECT_GT(highest, 1.2 * lowest) << "mortar and bricks differ";
    EXPECT_GT(tilted, 5) << "joint edges tilt the normal";
    EXPECT_LT(tilted, 150) << "brick faces stay flat";
    EXPECT_NEAR(highest, albedo_from_srgb(0xcc8844).x * 1.45, 1e-9);  // mortar: the lightest

    Hit road = wall;
    road.kind = ObjectKind::Road;
    road.material = kAsphalt;
    road.shading_normal = road.geometric_normal;
    EXPECT_EQ(surface_material(table, &looks, road).albedo.x, table[kAsphalt].albedo.x);
    EXPECT_EQ(road.shading_normal.y, -1);
}
