// Steep steps on a height field drawn as a stair (common/stairs.h, render/geometry/stair_geometry.h):
// treads at increasing heights with equal risers no higher than kStairMaxRiser, side faces down
// into the ground, the same in both geometry modes; shallow steps and steps without a field
// stay draped strips.
#include <cmath>
#include <random>
#include <set>

#include <gtest/gtest.h>

#include "common/ground.h"
#include "common/stairs.h"
#include "render/geometry/build_render_scene.h"
#include "render/geometry/path_geometry.h"
#include "render/geometry/stair_geometry.h"

using namespace citygen;

namespace {

// A hillside rising north over [-50, 50]^2, 2 m cells: z = 0.5 y.
HeightField hillside() {
    HeightField f;
    f.origin = {-50, -50};
    f.cell = 2;
    f.nx = f.ny = 51;
    for (uint32_t j = 0; j < f.ny; ++j)
        for (uint32_t i = 0; i < f.nx; ++i) f.heights.push_back(static_cast<float>(0.5 * (-50.0 + 2 * j)));
    return f;
}

PathEdge steps(Vec2 a, Vec2 b) {
    PathEdge p;
    p.path_class = PathClass::Steps;
    p.centreline = {a, b};
    p.width = 2;
    const Vec2 n = perp_left(normalize(b - a)) * 1.0;
    p.quad = {a - n, b - n, b + n, a + n};
    return p;
}

// Steps straight up the hillside (5 m over 10 m: 50%), down it the other way round, and steps
// across it rising 0.5 m over 20 m (2.5%).
Scene hillside_with_steps() {
    Scene s;
    s.terrain = hillside();
    s.paths = {steps({0, -10}, {0, 0}), steps({10, 30}, {10, 20}), steps({10, 0}, {30, 1})};
    return s;
}

bool hit_from_above(const RenderScene& scene, Vec2 p, Hit& hit) {
    return scene.intersect(Ray{{p.x, p.y, 200}, {0, 0, -1}, 0, 1e30}, hit);
}

}  // namespace

TEST(StairGeometry, SteepStepsClimbInTreadsOfEqualRiseAndShallowStepsStayDraped) {
    const Scene s = hillside_with_steps();
    StairPlan plan;
    ASSERT_TRUE(plan_stair(s, s.paths[0], &plan));
    EXPECT_EQ(plan.steps, 28) << "ceil(5 m / 0.18 m)";
    EXPECT_NEAR(plan.z_low, -5, 1e-6);
    EXPECT_NEAR(plan.z_high, 0, 1e-6);
    EXPECT_LE(plan.rise(), kStairMaxRiser);
    StairPlan down;
    ASSERT_TRUE(plan_stair(s, s.paths[1], &down)) << "drawn from its low end, whichever way the way runs";
    EXPECT_NEAR(down.low.y, 20, 1e-9);
    EXPECT_FALSE(plan_stair(s, s.paths[2], &plan)) << "2.5%: a ramp would do";

    const auto stored = build_render_scene(s, GeometryModes{});
    Hit hit;
    // Up the centreline and along both edges of the strip: flat treads rising by equal risers.
    for (double x : {-0.9, 0.0, 0.9}) {
        std::set<long> treads;
        double last = plan.z_low + kPathLift;  // the low end's ground: the first riser rises from it
        for (double y = -9.99; y < 0; y += 0.05) {
            ASSERT_TRUE(hit_from_above(*stored, {x, y}, hit)) << y;
            ASSERT_EQ(hit.kind, ObjectKind::Path) << y;
            EXPECT_EQ(hit.object, 0u);
            const double z = 200 - hit.t;
            EXPECT_GE(z, ground_height(s, x, y) + kPathLift) << "above the ground at " << y;
            EXPECT_GE(z, last - 1e-4) << "never down when going up, at " << y;
            EXPECT_LE(z - last, kStairMaxRiser + 1e-4) << y;
            if (z > last + 1e-4) {
                // Each tread at the top of its riser: z_low + lift + k * rise.
                const double k = (z - plan.z_low - kPathLift) / plan.rise();
                EXPECT_NEAR(k, std::round(k), 1e-3) << y;
                treads.insert(std::lround(k));
            }
            last = z;
        }
        EXPECT_EQ(treads.size(), 28u) << x;
        EXPECT_NEAR(last, 0 + kPathLift, 1e-4) << "the top tread level with the ground at the high end";
    }
    // From the side, under a tread and above the ground beside it: the side face, not the air.
    const double tread_z = plan.z_low + kPathLift + 14 * plan.rise();  // tread 13, over y in [-5.36, -5]
    ASSERT_TRUE(stored->intersect(Ray{{-20, -5.2, tread_z - 0.05}, {1, 0, 0}, 0, 1e30}, hit));
    EXPECT_EQ(hit.kind, ObjectKind::Path);
    EXPECT_NEAR(hit.t, 19, 1e-3);
    // Along the stair from below, just over a tread: the next riser, facing down the stair.
    ASSERT_TRUE(stored->intersect(Ray{{0, -12, tread_z + 0.05}, {0, 1, 0}, 0, 1e30}, hit));
    EXPECT_EQ(hit.kind, ObjectKind::Path);
    EXPECT_NEAR(-12 + hit.t, -5, 1e-3);
    EXPECT_LT(hit.geometric_normal.y, -0.99);

    // The shallow steps: draped, at the ground plus the path's lift.
    ASSERT_TRUE(hit_from_above(*stored, {20, 0.5}, hit));
    EXPECT_EQ(hit.kind, ObjectKind::Path);
    EXPECT_EQ(hit.object, 2u);
    EXPECT_NEAR(200 - hit.t, ground_height(s, 20, 0.5) + kPathLift, 1e-4);
}

TEST(StairGeometry, BothGeometryModesDrawTheSameStair) {
    const Scene s = hillside_with_steps();
    GeometryModes procedural;
    procedural[GeometryClass::Paths] = GeometryMode::Procedural;
    const auto stored = build_render_scene(s, GeometryModes{});
    const auto proc = build_render_scene(s, procedural);
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> u(-1, 1);
    int on_stair = 0, on_risers = 0, mismatches = 0;
    for (int k = 0; k < 4000; ++k) {
        const Vec3 origin{20 * u(rng), -5 + 20 * u(rng), 5 + 10 * (u(rng) + 1)};
        const Vec3 target{1.2 * u(rng), -5 + 5.2 * u(rng), -5 + 5 * (u(rng) + 1) / 2};
        const Ray ray{origin, normalize(target - origin), 0, 1e30};
        Hit a, b;
        const bool ha = stored->intersect(ray, a), hb = proc->intersect(ray, b);
        ASSERT_EQ(ha, hb) << k;
        if (!ha) continue;
        on_stair += a.kind == ObjectKind::Path && a.object == 0;
        on_risers += a.kind == ObjectKind::Path && a.object == 0 && std::fabs(a.geometric_normal.z) < 0.1;
        if (a.kind != b.kind || a.object != b.object || std::fabs(a.t - b.t) > 0.01) ++mismatches;
    }
    EXPECT_GT(on_stair, 1500);
    EXPECT_GT(on_risers, 200) << "a stair's risers and sides, not a draped strip";
    EXPECT_LE(mismatches, 8) << "edges hit within float rounding (" << on_stair << " on the stair)";
}

TEST(StairGeometry, WithoutAFieldStepsAreADrapedStripAsBefore) {
    Scene s = hillside_with_steps();
    s.terrain = {};
    StairPlan plan;
    EXPECT_FALSE(plan_stair(s, s.paths[0], &plan));
    Scene footways = s;
    for (PathEdge& p : footways.paths) p.path_class = PathClass::Footway;  // the same material
    const TriangleMesh a = build_stored_paths(s), b = build_stored_paths(footways);
    EXPECT_EQ(a.vertices, b.vertices);
    EXPECT_EQ(a.indices, b.indices);
}
