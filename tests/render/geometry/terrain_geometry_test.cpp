// Terrain on a height field: the stored mesh, the procedural block walker, and everything that
// stands on the ground (buildings at their lowest corner, trees, lamps, roads draped).
#include <algorithm>
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "render/geometry/build_render_scene.h"
#include "render/geometry/ground.h"
#include "render/geometry/lamp_shape.h"
#include "render/geometry/stored_geometry.h"
#include "render/geometry/terrain_geometry.h"
#include "tests/render/small_town.h"
#include "tests/test_scenes.h"

using namespace citygen;
using namespace citygen::test;

namespace {

// A field over [-100, 100]^2 with `cell` spacing: two hills and a slope, never flat.
HeightField hilly_field(double cell) {
    HeightField f;
    f.origin = {-100, -100};
    f.cell = cell;
    f.nx = f.ny = static_cast<uint32_t>(std::lround(200 / cell)) + 1;
    for (uint32_t j = 0; j < f.ny; ++j)
        for (uint32_t i = 0; i < f.nx; ++i) {
            const double x = f.origin.x + i * cell, y = f.origin.y + j * cell;
            f.heights.push_back(static_cast<float>(0.05 * x + 12 * std::exp(-((x - 30) * (x - 30) + y * y) / 900) +
                                                   6 * std::exp(-((x + 40) * (x + 40) + (y - 40) * (y - 40)) / 400)));
        }
    return f;
}

Scene scene_on(const HeightField& field) {
    Scene s = small_town();
    s.terrain = field;
    return s;
}

}  // namespace

TEST(TerrainGeometry, FieldMeshHeightsAreTheFieldsAtItsNodes) {
    const Scene s = scene_on(hilly_field(10));
    const TriangleMesh mesh = build_stored_terrain(s);
    const HeightField& f = s.terrain;
    ASSERT_GE(mesh.vertex_count(), size_t{f.nx} * f.ny);
    EXPECT_EQ(mesh.triangle_count(), 2u * (f.nx - 1) * (f.ny - 1) + 2 * terrain_skirt(s).size());
    for (uint32_t j = 0; j < f.ny; ++j)
        for (uint32_t i = 0; i < f.nx; ++i) {
            const Vec3 v = mesh.vertex(j * f.nx + i);
            EXPECT_NEAR(v.z, f.at(v.x, v.y), 1e-4) << i << "," << j;
            EXPECT_NEAR(ground_height(s, v.x, v.y), f.at(v.x, v.y), 1e-4);
        }
}

TEST(TerrainGeometry, NoFieldKeepsTheFlatPlane) {
    Scene s = small_town();
    s.ground.z = 1.5;
    const TriangleMesh mesh = build_stored_terrain(s);
    EXPECT_EQ(mesh.triangle_count(), 2u);
    for (size_t v = 0; v < mesh.vertex_count(); ++v) EXPECT_EQ(mesh.vertex(v).z, 1.5f);
    EXPECT_EQ(ground_height(s, 17, -3), 1.5);
    EXPECT_EQ(building_base(s, s.buildings[0]), 1.5);
}

TEST(TerrainGeometry, RaysHitTheProceduralTerrainWhereTheyHitTheStoredMesh) {
    Scene s = scene_on(hilly_field(5));
    s.buildings.clear();
    s.roads.clear();
    s.sidewalks.clear();
    s.lamps.clear();
    GeometryModes procedural_terrain;
    procedural_terrain[GeometryClass::Terrain] = GeometryMode::Procedural;
    const auto stored = build_render_scene(s, GeometryModes{});
    const auto procedural = build_render_scene(s, procedural_terrain);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1, 1);
    int hits = 0, grazing = 0;
    for (int k = 0; k < 4000; ++k) {
        // From above, from low over the hills and along the ground towards the skirt.
        const Vec3 origin{150 * u(rng), 150 * u(rng), 5 + 40 * (u(rng) + 1)};
        const Vec3 direction = normalize(Vec3{u(rng), u(rng), -0.05 - 0.6 * (u(rng) + 1)});
        Hit a, b;
        const bool ha = stored->intersect(Ray{origin, direction, 0, 1e30}, a);
        const bool hb = procedural->intersect(Ray{origin, direction, 0, 1e30}, b);
        ASSERT_EQ(ha, hb) << k;
        if (!ha) continue;
        ++hits;
        EXPECT_EQ(a.kind, ObjectKind::Terrain);
        EXPECT_EQ(b.kind, ObjectKind::Terrain);
        if (std::abs(a.t - b.t) > 0.01) {
            ++grazing;
        } else {
            EXPECT_GT(dot(a.geometric_normal, b.geometric_normal), 0.999) << k;
        }
    }
    EXPECT_GT(hits, 3000);
    EXPECT_LE(grazing, 4) << "hits more than 1 cm apart";
}

TEST(TerrainGeometry, ProceduralTerrainIsTenTimesSmallerThanStoredAt2m) {
    const Scene s = scene_on(hilly_field(2));
    GeometryModes procedural_terrain;
    procedural_terrain[GeometryClass::Terrain] = GeometryMode::Procedural;
    auto terrain_bytes = [](const RenderScene& scene) {
        size_t bytes = 0;
        for (const auto& g : scene.geometries())
            if (g->kind() == ObjectKind::Terrain) bytes += g->buffer_bytes();
        return bytes;
    };
    const size_t stored = terrain_bytes(*build_render_scene(s, GeometryModes{}));
    const size_t procedural = terrain_bytes(*build_render_scene(s, procedural_terrain));
    EXPECT_GT(procedural, s.terrain.heights.size() * sizeof(float) - 1);  // it keeps the heights
    EXPECT_LE(procedural * 10, stored) << procedural << " vs " << stored << " bytes";
}

TEST(TerrainGeometry, BuildingOnASlopeStandsAtItsLowestCorner) {
    // A plane rising 0.2 m per metre eastwards; the block spans x = 10..30.
    HeightField slope;
    slope.origin = {-100, -100};
    slope.cell = 4;
    slope.nx = slope.ny = 51;
    for (uint32_t j = 0; j < slope.ny; ++j)
        for (uint32_t i = 0; i < slope.nx; ++i) slope.heights.push_back(static_cast<float>(0.2 * (i * 4.0 - 100)));
    Scene s = small_town();
    s.terrain = slope;
    s.buildings = {box_building(10, 10, 30, 20, 12)};
    EXPECT_NEAR(building_base(s, s.buildings[0]), 2.0, 1e-5);
    for (const GeometryModes& modes : {GeometryModes{}, GeometryModes::all(GeometryMode::Procedural)}) {
        const auto scene = build_render_scene(s, modes, FacadeOptions{});
        Hit hit;
        // The roof is 12 m above the lowest corner, not above the ground under it.
        ASSERT_TRUE(scene->intersect(Ray{{25, 15, 100}, {0, 0, -1}, 0, 1e30}, hit));
        EXPECT_EQ(hit.kind, ObjectKind::Building);
        EXPECT_NEAR(100 - hit.t, 14.0, 1e-3);
        // The walls reach the ground all round: rays skimming 5 cm above the ground meet the
        // downhill wall (at its foot) and the uphill one (its foot is below the ground), no gap.
        ASSERT_TRUE(scene->intersect(Ray{{0, 15, ground_height(s, 10, 15) + 0.05}, {1, 0, 0}, 0, 1e30}, hit));
        EXPECT_EQ(hit.kind, ObjectKind::Building);
        EXPECT_NEAR(hit.t, 10, 1e-3);
        ASSERT_TRUE(scene->intersect(Ray{{31, 15, ground_height(s, 31, 15) + 0.05}, {-1, 0, 0}, 0, 1e30}, hit));
        EXPECT_EQ(hit.kind, ObjectKind::Building);
        EXPECT_NEAR(hit.t, 1, 1e-3);
    }
}

TEST(TerrainGeometry, LampsRoadsAndTreesLieOnTheGround) {
    Scene s = scene_on(hilly_field(10));
    s.buildings.clear();
    Tree tree;
    tree.position = {30, 0};
    tree.height = 8;
    s.trees.push_back(tree);
    const double g = ground_height(s, 30, 0);
    EXPECT_GT(g, 10);  // on the hill
    Lamp lamp;
    lamp.position = {60, -21, 0};
    s.lamps.push_back(lamp);
    EXPECT_NEAR(lamp_shape(lamp, lamp_ground(StandingSurface(s), lamp)).base.z,
                ground_height(s, lamp.position.x, lamp.position.y) + lamp.position.z, 1e-9);
    for (const GeometryModes& modes : {GeometryModes{}, GeometryModes::all(GeometryMode::Procedural)}) {
        const auto scene = build_render_scene(s, modes, FacadeOptions{});
        Hit hit;
        // Down onto the road: exactly its lift above the ground under it, not at z = 0 inside the hill.
        const Vec2 r = s.roads[0].quad[0] * 0.5 + s.roads[0].quad[2] * 0.5;
        ASSERT_TRUE(scene->intersect(Ray{{r.x, r.y, 200}, {0, 0, -1}, 0, 1e30}, hit));
        EXPECT_EQ(hit.kind, ObjectKind::Road);
        EXPECT_NEAR(200 - hit.t, ground_height(s, r.x, r.y) + kRoadLift, 1e-3);
        // And everywhere along it, off the field's nodes and diagonals.
        for (double x = -47.3; x < 48; x += 3.7) {
            ASSERT_TRUE(scene->intersect(Ray{{x, -25.1, 200}, {0, 0, -1}, 0, 1e30}, hit));
            EXPECT_EQ(hit.kind, ObjectKind::Road);
            EXPECT_NEAR(200 - hit.t, ground_height(s, x, -25.1) + kRoadLift, 1e-3) << x;
        }
        // Sideways at the tree's trunk, a metre above the hill's ground.
        ASSERT_TRUE(scene->intersect(Ray{{20, 0, g + 1}, {1, 0, 0}, 0, 1e30}, hit));
        EXPECT_EQ(hit.kind, ObjectKind::Tree);
    }
}

TEST(TerrainGeometry, TheFieldSinksUnderTheSeaButNotUnderLand) {
    Scene s = scene_on(hilly_field(10));
    LandCover sea;
    sea.cover = LandCoverClass::Sea;
    sea.outer = square(-100, -100, 50);  // nodes x, y in [-100, -50]
    sea.holes = {square(-80, -80, 15)};  // an island: nodes (-70, -70) inside it
    std::reverse(sea.holes[0].begin(), sea.holes[0].end());
    s.land_cover.push_back(sea);
    const HeightField before = s.terrain;
    sink_field_under_sea(s);
    const HeightField& f = s.terrain;
    int sunk = 0;
    for (uint32_t j = 0; j < f.ny; ++j)
        for (uint32_t i = 0; i < f.nx; ++i) {
            const Vec3 p = field_node(f, i, j);
            const size_t k = static_cast<size_t>(j) * f.nx + i;
            const bool in_sea = point_in_ring({p.x, p.y}, sea.outer) && !point_in_ring({p.x, p.y}, sea.holes[0]);
            if (in_sea && p.x > -99 && p.y > -99 && p.x < -51 && p.y < -51) {
                EXPECT_LE(f.heights[k], kSeaFloor) << p.x << "," << p.y;
                ++sunk;
            } else if (!in_sea && (p.x > -49 || p.y > -49 || (p.x == -70 && p.y == -70))) {
                EXPECT_EQ(f.heights[k], before.heights[k]) << p.x << "," << p.y;
            }
        }
    EXPECT_GT(sunk, 10);
}

TEST(TerrainGeometry, APierInTheSeaIsNotSunk) {
    Scene s = scene_on(hilly_field(10));
    LandCover sea, pier;
    sea.cover = LandCoverClass::Sea;
    sea.outer = square(-100, -100, 50);
    pier.cover = LandCoverClass::Paved;
    pier.outer = square(-80, -80, 20);
    s.land_cover = {sea, pier};
    const HeightField before = s.terrain;
    sink_field_under_sea(s);
    EXPECT_EQ(s.terrain.at(-70, -70), before.at(-70, -70)) << "under the pier";
    EXPECT_LE(s.terrain.at(-95, -60), kSeaFloor) << "the sea beside it";
}
