// Bridges on a height field (render/geometry/bridge_geometry.h): the deck at its own height over
// a valley, its slab and piers, the sidewalks on it, the same in both geometry modes; without a
// field a bridge is any road.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "common/ground.h"
#include "render/geometry/bridge_geometry.h"
#include "render/geometry/build_render_scene.h"
#include "render/geometry/lamp_shape.h"
#include "render/geometry/path_geometry.h"
#include "render/geometry/stored_geometry.h"
#include "render/materials/materials.h"

using namespace citygen;

namespace {

// A valley along y over [-100, 100]^2, 2 m cells: z = 0.5 |x|, 0 at its floor, 40 m at x = 80.
HeightField valley() {
    HeightField f;
    f.origin = {-100, -100};
    f.cell = 2;
    f.nx = f.ny = 101;
    for (uint32_t j = 0; j < f.ny; ++j)
        for (uint32_t i = 0; i < f.nx; ++i) f.heights.push_back(static_cast<float>(0.5 * std::fabs(-100.0 + 2 * i)));
    return f;
}

RoadEdge road(int64_t from, int64_t to, Vec2 a, Vec2 b, bool bridge) {
    RoadEdge r;
    r.from_node = from;
    r.to_node = to;
    r.centreline = {a, b};
    r.width = 8;
    r.bridge = bridge;
    const Vec2 n = perp_left(normalize(b - a)) * 4.0;
    r.quad = {a - n, b - n, b + n, a + n};
    return r;
}

// Roads on the ground up to the valley's rims at x = +-60 (30 m up), a bridge of two edges
// across, and a sidewalk strip along its east half.
Scene valley_with_bridge() {
    Scene s;
    s.terrain = valley();
    s.roads = {road(10, 1, {-90, 0}, {-60, 0}, false), road(1, 2, {-60, 0}, {0, 0}, true),
               road(2, 3, {0, 0}, {60, 0}, true), road(3, 11, {60, 0}, {90, 0}, false)};
    Sidewalk walk;
    walk.road = 2;
    walk.polygon = {{0, 4}, {60, 4}, {60, 6}, {0, 6}};
    s.sidewalks = {walk};
    return s;
}

bool hit_from_above(const RenderScene& scene, Vec2 p, Hit& hit) {
    return scene.intersect(Ray{{p.x, p.y, 200}, {0, 0, -1}, 0, 1e30}, hit);
}

}  // namespace

TEST(BridgeGeometry, TheDeckSpansTheValleyAtItsEndsHeightWithASlabAndPiers) {
    const Scene s = valley_with_bridge();
    const auto stored = build_render_scene(s, GeometryModes{});
    Hit hit;
    for (double x : {-50.0, -20.0, 0.0, 10.0, 50.0}) {
        ASSERT_TRUE(hit_from_above(*stored, {x, 0}, hit)) << x;
        EXPECT_EQ(hit.kind, ObjectKind::Road) << x;
        EXPECT_NEAR(200 - hit.t, 30 + kRoadLift, 1e-3) << "level at the rims' height, not the valley's, at " << x;
    }
    ASSERT_TRUE(hit_from_above(*stored, {30, 5}, hit));
    EXPECT_EQ(hit.kind, ObjectKind::Sidewalk);
    EXPECT_GT(200 - hit.t, 30 + kRoadLift) << "the sidewalk on the deck, a curb above the road";
    // From below: the slab's underside, kDeckThickness under the surface.
    ASSERT_TRUE(stored->intersect(Ray{{-10, 0, 6}, {0, 0, 1}, 0, 1e30}, hit));
    EXPECT_EQ(hit.kind, ObjectKind::Road);
    EXPECT_NEAR(6 + hit.t, 30 - kDeckThickness, 1e-3);
    // From the side, under the deck's surface: the slab's side face, not the air.
    ASSERT_TRUE(stored->intersect(Ray{{-30, -50, 29.7}, {0, 1, 0}, 0, 1e30}, hit));
    EXPECT_EQ(hit.kind, ObjectKind::Road);
    EXPECT_NEAR(hit.t, 50 - 4, 1e-3);
    // Piers where the deck is high (every third of each 60 m edge): a horizontal ray along the
    // deck's axis under it meets the one at x = -20, 1 m thick.
    ASSERT_TRUE(stored->intersect(Ray{{-30, 0, 20}, {1, 0, 0}, 0, 1e30}, hit));
    EXPECT_EQ(hit.kind, ObjectKind::Road);
    EXPECT_NEAR(hit.t, 9.5, 1e-3);
    EXPECT_FALSE(deck_piers(s, bridge_decks(s)[1], s.roads[1].width).empty());
}

TEST(BridgeGeometry, BothGeometryModesDrawTheSameBridge) {
    const Scene s = valley_with_bridge();
    GeometryModes procedural;
    for (GeometryClass c : {GeometryClass::Roads, GeometryClass::Sidewalks}) procedural[c] = GeometryMode::Procedural;
    const auto stored = build_render_scene(s, GeometryModes{});
    const auto proc = build_render_scene(s, procedural);
    std::mt19937 rng(3);
    std::uniform_real_distribution<double> u(-1, 1);
    int on_bridge = 0, mismatches = 0;
    for (int k = 0; k < 4000; ++k) {
        const Vec3 origin{80 * u(rng), 60 * u(rng), 20 + 30 * (u(rng) + 1)};
        const Vec3 target{60 * u(rng), 8 * u(rng), 30 * (u(rng) + 1) / 2};
        const Ray ray{origin, normalize(target - origin), 0, 1e30};
        Hit a, b;
        const bool ha = stored->intersect(ray, a), hb = proc->intersect(ray, b);
        ASSERT_EQ(ha, hb) << k;
        if (!ha) continue;
        on_bridge += a.kind == ObjectKind::Road || a.kind == ObjectKind::Sidewalk;
        if (a.kind != b.kind || a.object != b.object || std::fabs(a.t - b.t) > 0.01) ++mismatches;
    }
    EXPECT_GT(on_bridge, 500);
    EXPECT_LE(mismatches, 4) << "edges hit within float rounding";
}

namespace {

// Footways on the ground to the valley's rims, a footbridge of two edges across meeting at a
// joint on the deck (node 2).
Scene valley_with_footbridge() {
    Scene s = valley_with_bridge();
    s.roads.clear();
    s.sidewalks.clear();
    for (const RoadEdge& r : valley_with_bridge().roads) {
        PathEdge p;
        p.from_node = r.from_node;
        p.to_node = r.to_node;
        p.centreline = r.centreline;
        p.width = 3;
        p.bridge = r.bridge;
        const Vec2 a = r.centreline.front(), b = r.centreline.back(), n = perp_left(normalize(b - a)) * 1.5;
        const Vec2 inset = normalize(b - a) * (p.from_node == 2 ? 1.5 : 0.0);
        const Vec2 outset = normalize(b - a) * (p.to_node == 2 ? 1.5 : 0.0);
        p.quad = {a + inset - n, b - outset - n, b - outset + n, a + inset + n};
        s.paths.push_back(p);
    }
    Joint j;
    j.edges = {1, 2};
    j.polygon = {{-1.5, -1.5}, {1.5, -1.5}, {1.5, 1.5}, {-1.5, 1.5}};
    s.path_joints = {j};
    return s;
}

}  // namespace

TEST(BridgeGeometry, AFootbridgeAndItsJointLieOnTheirDeckInBothModes) {
    const Scene s = valley_with_footbridge();
    GeometryModes procedural;
    procedural[GeometryClass::Paths] = GeometryMode::Procedural;
    const auto stored = build_render_scene(s, GeometryModes{});
    const auto proc = build_render_scene(s, procedural);
    for (const RenderScene* scene : {stored.get(), proc.get()}) {
        Hit hit;
        // The ground is 30 m up at both rims: a level deck 30 m over the valley's floor.
        for (Vec2 p : {Vec2{-30, 0}, Vec2{25, 0.5}}) {
            ASSERT_TRUE(hit_from_above(*scene, p, hit));
            EXPECT_EQ(hit.kind, ObjectKind::Path);
            EXPECT_NEAR(200 - hit.t, 30 + kPathLift, 1e-3) << p.x;
        }
        ASSERT_TRUE(hit_from_above(*scene, {0, 0}, hit));
        EXPECT_EQ(hit.kind, ObjectKind::PathJoint);
        EXPECT_NEAR(200 - hit.t, 30 + kPathLift, 1e-3) << "the joint on the deck";
        ASSERT_TRUE(hit_from_above(*scene, {-80, 0}, hit));
        EXPECT_NEAR(200 - hit.t, ground_height(s, -80, 0) + kPathLift, 1e-3) << "a footway on the ground";
        // Its slab from below, over the valley's floor (15 m there).
        ASSERT_TRUE(scene->intersect(Ray{{-30, 0, 20}, {0, 0, 1}, 0, 1e30}, hit));
        EXPECT_NEAR(20 + hit.t, 30 - kDeckThickness, 1e-3);
    }
}

TEST(BridgeGeometry, ALampOnABridgeStandsOnItsDeckAndOneBesideItOnTheGround) {
    const Scene s = valley_with_bridge();
    const StandingSurface surface(s);
    Lamp on, beside;
    on.position = {-20, 5.5, 0};      // on the bridge's edge, 1.5 m beyond the carriageway
    beside.position = {-20, 12, 0};  // 8 m beyond it, in the valley
    EXPECT_NEAR(lamp_ground(surface, on), 30, 1e-6);
    EXPECT_NEAR(lamp_ground(surface, beside), 10, 1e-6);
    Lamp away;
    away.position = {-80, 0, 0};  // on the road to the bridge
    EXPECT_NEAR(lamp_ground(surface, away), ground_height(s, -80, 0), 1e-9);
}

TEST(BridgeGeometry, ALampOnAFootbridgeStandsOnItsDeck) {
    const Scene s = valley_with_footbridge();
    const StandingSurface surface(s);
    Lamp on, beside;
    on.position = {-20, 2.2, 0};     // at the railing, 0.7 m beyond the 3 m strip
    beside.position = {-20, 4, 0};   // 2.5 m beyond it, in the valley
    EXPECT_NEAR(lamp_ground(surface, on), 30, 1e-6);
    EXPECT_NEAR(lamp_ground(surface, beside), ground_height(s, -20, 4), 1e-6);
    EXPECT_LT(lamp_ground(surface, beside), 20);
}

TEST(BridgeGeometry, ADeckHundredsOfKilometresLongIsFoundWithoutIndexingEveryCellAcrossIt) {
    Scene s = valley_with_bridge();
    s.roads = {road(1, 2, {-60, -60}, {400000, 400000}, true)};  // what a hostile scene may hold
    const StandingSurface surface(s);  // its bounding box holds 39 million 64 m cells
    Lamp on;
    on.position = {0, 0, 0};
    const double deck = deck_height(bridge_decks(s)[0], {0, 0});
    EXPECT_GT(deck, 29);
    EXPECT_NEAR(lamp_ground(surface, on), deck, 1e-9);
}

TEST(BridgeGeometry, WithoutAFieldABridgeIsAnyRoad) {
    Scene s = valley_with_bridge();
    s.terrain = {};
    EXPECT_TRUE(drawn_decks(s).empty());
    Scene plain = s;
    for (RoadEdge& r : plain.roads) r.bridge = false;
    const TriangleMesh a = build_stored_roads(s), b = build_stored_roads(plain);
    EXPECT_EQ(a.vertices, b.vertices);
    EXPECT_EQ(a.indices, b.indices);
}
