// Stored geometry: what a hit reports, roofs with holes triangulated to their area, and the
// geometry mode option.
#include <algorithm>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "common/error.h"
#include "render/geometry/build_render_scene.h"
#include "render/geometry/stored_geometry.h"
#include "render/geometry/triangulate_polygon.h"
#include "tests/render/small_town.h"

using namespace citygen;
using namespace citygen::test;

TEST(StoredGeometry, HitsReportObjectKindIndexAndOutwardNormal) {
    const Scene s = small_town();
    const auto scene = build_render_scene(s, GeometryModes{});
    Hit hit;
    // Down onto the tall block's roof.
    ASSERT_TRUE(scene->intersect(Ray{{20, 10, 100}, {0, 0, -1}, 0, 1e30}, hit));
    EXPECT_EQ(hit.kind, ObjectKind::Building);
    EXPECT_EQ(hit.object, 1u);
    EXPECT_EQ(hit.material, kRoof);
    EXPECT_NEAR(hit.t, 70, 1e-3);
    EXPECT_NEAR(hit.geometric_normal.z, 1, 1e-9);
    // Westwards into the courtyard's inner wall (a hole ring): its normal faces the courtyard.
    ASSERT_TRUE(scene->intersect(Ray{{-5, -5, 5}, {-1, 0, 0}, 0, 1e30}, hit));
    EXPECT_EQ(hit.kind, ObjectKind::Building);
    EXPECT_EQ(hit.object, 0u);
    EXPECT_EQ(hit.material, kFacade);
    EXPECT_NEAR(hit.t, 7, 1e-3);
    EXPECT_NEAR(hit.geometric_normal.x, 1, 1e-9);
    // The courtyard has no roof: straight down from above lands on the ground.
    ASSERT_TRUE(scene->intersect(Ray{{-5, -5, 100}, {0, 0, -1}, 0, 1e30}, hit));
    EXPECT_EQ(hit.kind, ObjectKind::Terrain);
    // Road and raised sidewalk with its curb.
    ASSERT_TRUE(scene->intersect(Ray{{0, -27, 10}, {0, 0, -1}, 0, 1e30}, hit));
    EXPECT_EQ(hit.kind, ObjectKind::Road);
    EXPECT_EQ(hit.material, kAsphalt);
    ASSERT_TRUE(scene->intersect(Ray{{0, -23, 10}, {0, 0, -1}, 0, 1e30}, hit));
    EXPECT_EQ(hit.kind, ObjectKind::Sidewalk);
    EXPECT_NEAR(hit.position.z, kRoadLift + 0.15, 1e-4);
    ASSERT_TRUE(scene->intersect(Ray{{0, -27, 0.1}, {0, 1, 0}, 0, 1e30}, hit));
    EXPECT_EQ(hit.kind, ObjectKind::Sidewalk);
    EXPECT_EQ(hit.material, kCurb);
    EXPECT_NEAR(hit.geometric_normal.y, -1, 1e-9);
}

TEST(StoredGeometry, RoofWithHoleCoversExactlyTheRingArea) {
    const Ring outer = square(0, 0, 10);
    Ring hole = square(3, 3, 4);
    std::reverse(hole.begin(), hole.end());
    // An L-shape (non-convex) in the outer ring too.
    const Ring l_shape = {{0, 0}, {10, 0}, {10, 4}, {4, 4}, {4, 10}, {0, 10}};
    for (const auto& [ring, holes, area] : {std::make_tuple(outer, std::vector<Ring>{hole}, 100.0 - 16.0),
                                            std::make_tuple(l_shape, std::vector<Ring>{}, 64.0)}) {
        const PolygonTriangulation t = triangulate_polygon(ring, holes);
        double sum = 0;
        for (const auto& tri : t.triangles) {
            const double a = 0.5 * cross(t.points[tri[1]] - t.points[tri[0]], t.points[tri[2]] - t.points[tri[0]]);
            EXPECT_GT(a, 0) << "triangles are counter-clockwise";
            sum += a;
        }
        EXPECT_NEAR(sum, area, 1e-9);
    }
}

TEST(StoredGeometry, GeometryModeParsingAndProceduralRequest) {
    EXPECT_EQ(parse_geometry_mode("stored", "--geometry-roads"), GeometryMode::Stored);
    EXPECT_EQ(parse_geometry_mode("procedural", "--geometry-roads"), GeometryMode::Procedural);
    EXPECT_THROW(parse_geometry_mode("triangles", "--geometry-roads"), Error);
}
