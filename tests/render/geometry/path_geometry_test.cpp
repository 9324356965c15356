// How render paints paths: rails and sleepers on railways, rails only on street tram tracks.
#include <gtest/gtest.h>

#include "render/geometry/path_geometry.h"
#include "render/materials/materials.h"

using namespace citygen;

TEST(PathRender, RailsAndSleepersOnRailwaysRailsOnlyOnStreetTramTracks) {
    PathEdge rail;
    rail.centreline = {{0, 0}, {100, 0}};
    rail.width = 3;
    rail.path_class = PathClass::Rail;
    EXPECT_EQ(path_surface_material(path_paint(rail), {10.3, 0.75}), kRailSteel);
    EXPECT_EQ(path_surface_material(path_paint(rail), {10.3, -0.75}), kRailSteel);
    int sleepers = 0, ballast = 0;
    for (double x = 0; x < 6; x += 0.05) {
        const uint16_t m = path_surface_material(path_paint(rail), {x, 0.3});
        sleepers += m == kSleeper;
        ballast += m == kBallast;
    }
    EXPECT_GT(sleepers, 20);
    EXPECT_GT(ballast, 20);
    PathEdge tram = rail;
    tram.path_class = PathClass::Tram;
    EXPECT_EQ(path_surface_material(path_paint(tram), {10.3, 0.75}), kRailSteel);
    for (double x = 0; x < 6; x += 0.05) EXPECT_NE(path_surface_material(path_paint(tram), {x, 0.3}), kSleeper);
    PathEdge footway = rail;
    footway.path_class = PathClass::Footway;
    EXPECT_EQ(path_surface_material(path_paint(footway), {10.3, 0.75}), kPathPaving);
}
