// Facade styles from a building's type, material and height, and the wall layouts they give.
#include <gtest/gtest.h>

#include "render/facade/facade.h"

using namespace citygen;

TEST(FacadeStyle, ByTypeMaterialAndHeight) {
    Building b;
    b.outer = {{0, 0}, {20, 0}, {20, 10}, {0, 10}};
    b.height = 9;
    b.type = "garage";
    EXPECT_EQ(facade_style(b), FacadeStyle::Plain);
    EXPECT_TRUE(make_wall_layout(FacadeOptions{}, building_wall_input(b, 0)).plain());
    b.type = "office";
    b.height = 60;
    EXPECT_EQ(facade_style(b), FacadeStyle::CurtainWall);
    const WallLayout glass = make_wall_layout(FacadeOptions{}, building_wall_input(b, 0));
    EXPECT_FALSE(glass.balconies);
    EXPECT_GT(glass.window.u1 - glass.window.u0, 0.9 * glass.slot_width);
    b.type = "office";
    b.height = 20;
    EXPECT_EQ(facade_style(b), FacadeStyle::Office);
    const WallLayout office = make_wall_layout(FacadeOptions{}, building_wall_input(b, 0));
    EXPECT_FALSE(office.balconies);
    EXPECT_GT(office.window.u1 - office.window.u0, 0.9 * office.slot_width) << "ribbon windows";
    b.type = "house";  // the same wall as a house: lower storeys, so more of them
    EXPECT_GT(make_wall_layout(FacadeOptions{}, building_wall_input(b, 0)).floors, office.floors);
    b.height = 9;
    FacadeOptions always_shops;
    always_shops.shop_probability = 1;
    EXPECT_FALSE(make_wall_layout(always_shops, building_wall_input(b, 0)).shop);
    b.type = "retail";
    EXPECT_TRUE(make_wall_layout(FacadeOptions{}, building_wall_input(b, 0)).shop);
}
