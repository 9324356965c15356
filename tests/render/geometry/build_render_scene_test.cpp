// Building the render scene: progress on stderr unless quiet; the classes freed on the way.
#include <string>

#include <gtest/gtest.h>

#include "render/geometry/build_render_scene.h"
#include "render/materials/materials.h"
#include "tests/render/small_town.h"

using namespace citygen;
using namespace citygen::test;

TEST(SceneBuild, ShowsGeometryAndBvhProgressUnlessQuiet) {
    // Shown from the start here (show_after 0) so a tiny scene exercises what Monaco needs.
    for (const GeometryMode mode : {GeometryMode::Stored, GeometryMode::Procedural}) {
        testing::internal::CaptureStderr();
        build_render_scene(small_town(), GeometryModes::all(mode), FacadeOptions{}, ProgressSettings{false, 0.0});
        const std::string shown = testing::internal::GetCapturedStderr();
        EXPECT_NE(shown.find("geometry ["), std::string::npos) << shown;
        EXPECT_NE(shown.find("BVH ["), std::string::npos) << shown;
        EXPECT_NE(shown.find("100.0%"), std::string::npos) << shown;
        testing::internal::CaptureStderr();
        build_render_scene(small_town(), GeometryModes::all(mode), FacadeOptions{}, ProgressSettings{true, 0.0});
        EXPECT_EQ(testing::internal::GetCapturedStderr(), "");
    }
}

// render frees each class once its geometry is built, before the buildings' geometry is made
// (main.cpp): what the geometry paints at shading time (road markings, rail tracks) must be its
// own copy, so the hits are the same as from a scene kept whole.
TEST(SceneBuild, ClassesFreedBeforeTheBuildingsGiveTheSameHits) {
    Scene town = small_town();
    RoadEdge& road = town.roads[0];
    road.centreline = {{-50, -27}, {50, -27}};
    road.width = 6;
    road.lanes_forward = road.lanes_backward = 1;
    road.centre_line = CentreLine::Dashed;
    road.edge_lines = true;
    Crossing zebra;
    zebra.road = 0;
    zebra.position = {0, -27};
    town.crossings.push_back(zebra);
    PathEdge rail;
    rail.centreline = {{-50, 35}, {50, 35}};
    rail.quad = {{-50, 33}, {50, 33}, {50, 37}, {-50, 37}};
    rail.width = 4;
    rail.path_class = PathClass::Rail;
    town.paths.push_back(rail);
    Lamp lamp;
    lamp.position = {0, -23, 0};
    town.lamps.push_back(lamp);

    for (const GeometryMode mode : {GeometryMode::Stored, GeometryMode::Procedural}) {
        const auto whole = build_render_geometry(town, GeometryModes::all(mode));
        whole->commit(ProgressSettings{true});
        Scene freed = town;
        bool buildings_there = false;
        const auto release = [&] {
            release_geometry_only_classes(freed);
            buildings_there = !freed.buildings.empty();
        };
        const auto built =
            build_render_geometry(freed, GeometryModes::all(mode), FacadeOptions{}, ProgressSettings{true}, release);
        release_buildings(freed, false);
        built->commit(ProgressSettings{true});
        EXPECT_TRUE(buildings_there);
        EXPECT_TRUE(freed.roads.empty() && freed.paths.empty() && freed.crossings.empty() && freed.lamps.empty() &&
                    freed.buildings.empty());
        int hits = 0, painted = 0, rails = 0;
        for (double x = -49; x < 50; x += 0.37)
            for (double y = -49; y < 50; y += 0.41) {
                const Ray ray{{x, y, 100}, normalize(Vec3{0.3, 0.2, -1}), 0, 1e30};
                Hit a, b;
                const bool ha = whole->intersect(ray, a), hb = built->intersect(ray, b);
                ASSERT_EQ(ha, hb) << x << " " << y;
                if (!ha) continue;
                ++hits;
                painted += a.material == kPaintWhite;
                rails += a.material == kRailSteel || a.material == kSleeper;
                EXPECT_EQ(a.kind, b.kind);
                EXPECT_EQ(a.object, b.object);
                EXPECT_EQ(a.material, b.material) << x << " " << y;
                EXPECT_EQ(a.t, b.t);
            }
        EXPECT_GT(hits, 10000);
        EXPECT_GT(painted, 50);  // the markings and the rails are in view
        EXPECT_GT(rails, 50);
    }
}
