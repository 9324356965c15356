// Retaining walls (render/geometry/wall_geometry.h, common/retaining_wall.h): a slab along the
// wall from under the low side's ground to a parapet above the high side's, each wall its own
// object, the same in both geometry modes; none without a field.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "common/ground.h"
#include "common/retaining_wall.h"
#include "render/geometry/build_render_scene.h"
#include "render/geometry/wall_geometry.h"
#include "render/materials/materials.h"

using namespace citygen;

namespace {

// 2 m cells over [-100, 100]^2: 20 m north of y = 2, 17 m south of y = 0 (the ground osmparse
// steps at a 3 m wall along y = 1), and two walls: the stepped one eastwards (low side south),
// and a short stone one on the high side, bent.
Scene stepped_scene() {
    Scene s;
    HeightField& f = s.terrain;
    f.origin = {-100, -100};
    f.cell = 2;
    f.nx = f.ny = 101;
    for (uint32_t j = 0; j < f.ny; ++j)
        for (uint32_t i = 0; i < f.nx; ++i) f.heights.push_back(-100.0 + 2 * j >= 2 ? 20.0f : 17.0f);
    RetainingWall wall;
    wall.osm = {OsmType::Way, 7};
    wall.line = {{-40, 1}, {0, 1}, {40, 1}};
    wall.height = 3;
    RetainingWall bent;
    bent.osm = {OsmType::Way, 8};
    bent.line = {{-20, 30}, {0, 40}, {20, 31}};
    bent.height = 1;
    bent.material = WallMaterial::Stone;
    s.retaining_walls = {wall, bent};
    return s;
}

bool hit(const RenderScene& scene, Vec3 origin, Vec3 direction, Hit& h) {
    return scene.intersect(Ray{origin, normalize(direction), 0, 1e30}, h);
}

}  // namespace

TEST(WallGeometry, AWallStandsFromTheLowGroundToAParapetAboveTheHighGround) {
    const Scene s = stepped_scene();
    const auto scene = build_render_scene(s, GeometryModes{});
    Hit h;
    // From above on its line: its top, the parapet over the high side's 20 m.
    ASSERT_TRUE(hit(*scene, {10, 1, 100}, {0, 0, -1}, h));
    EXPECT_EQ(h.kind, ObjectKind::RetainingWall);
    EXPECT_EQ(h.object, 0u);
    EXPECT_NEAR(h.position.z, 20 + kRetainingWallParapet, 1e-4);
    EXPECT_EQ(h.material, kRetainingConcrete);
    // From the low side, level at 19.5 m (above the ramp at its foot, below the high ground): its face.
    ASSERT_TRUE(hit(*scene, {10, -20, 19.5}, {0, 1, 0}, h));
    EXPECT_EQ(h.kind, ObjectKind::RetainingWall);
    EXPECT_NEAR(h.position.y, 1 - 0.5 * kRetainingWallThickness, 1e-4);
    EXPECT_LT(h.geometric_normal.y, -0.99) << "the low side's face looks south";
    // Its foot is under the ground beside it.
    for (const WallStation& st : wall_stations(s, s.retaining_walls[0])) {
        EXPECT_LT(st.bottom, ground_height(s, st.right.x, st.right.y));
        EXPECT_LT(st.bottom, ground_height(s, st.left.x, st.left.y));
    }
    // The second wall is the second object, of stone.
    ASSERT_TRUE(hit(*scene, {0, 40, 100}, {0, 0, -1}, h));
    EXPECT_EQ(h.kind, ObjectKind::RetainingWall);
    EXPECT_EQ(h.object, 1u);
    EXPECT_EQ(h.material, kRetainingStone);
}

TEST(WallGeometry, BothGeometryModesDrawTheSameWall) {
    const Scene s = stepped_scene();
    GeometryModes procedural;
    procedural[GeometryClass::RetainingWalls] = GeometryMode::Procedural;
    const auto stored = build_render_scene(s, GeometryModes{});
    const auto proc = build_render_scene(s, procedural);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1, 1);
    int on_walls[2] = {0, 0}, mismatches = 0;
    for (int k = 0; k < 4000; ++k) {
        const Vec3 origin{60 * u(rng), 60 * u(rng), 22 + 10 * (u(rng) + 1)};
        const Vec3 target{45 * u(rng), 20 + 22 * u(rng), 19 + 2 * u(rng)};
        const Ray ray{origin, normalize(target - origin), 0, 1e30};
        Hit a, b;
        const bool ha = stored->intersect(ray, a), hb = proc->intersect(ray, b);
        ASSERT_EQ(ha, hb) << k;
        if (!ha) continue;
        if (a.kind == ObjectKind::RetainingWall && a.object < 2) ++on_walls[a.object];
        if (a.kind != b.kind || a.object != b.object || a.material != b.material || std::fabs(a.t - b.t) > 0.01)
            ++mismatches;
    }
    EXPECT_GT(on_walls[0], 100);
    EXPECT_GT(on_walls[1], 20);
    EXPECT_LE(mismatches, 4) << "edges hit within float rounding";
}

TEST(WallGeometry, WithoutAFieldNoWallIsDrawn) {
    Scene s = stepped_scene();
    s.terrain = {};
    EXPECT_TRUE(retaining_wall_faces(s, s.retaining_walls[0]).empty());
    const size_t with = build_render_scene(s, GeometryModes{})->geometries().size();
    s.retaining_walls.clear();
    EXPECT_EQ(with, build_render_scene(s, GeometryModes{})->geometries().size());
}
