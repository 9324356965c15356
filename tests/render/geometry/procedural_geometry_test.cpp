// Stored vs procedural geometry through Embree: for the same scene, rays must find the same
// object, material, distance and normal whichever mode built the geometry.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "common/rng.h"
#include "render/facade/facade.h"
#include "render/geometry/build_render_scene.h"
#include "render/geometry/procedural_geometry.h"
#include "render/geometry/stored_geometry.h"
#include "render/scene/render_scene.h"

using namespace citygen;

namespace {

Building box_building(int64_t id, Vec2 min, Vec2 max, double height, double min_height = 0) {
    Building b;
    b.osm = {OsmType::Way, id};
    b.outer = {min, {max.x, min.y}, max, {min.x, max.y}};
    b.height = height;
    b.min_height = min_height;
    return b;
}

// The ground and the scene's bounds: the box from min to max.
void set_ground(Scene& s, Vec2 min, Vec2 max) {
    s.ground.min = min;
    s.ground.max = max;
    s.header.bounds_min = min;
    s.header.bounds_max = max;
}

// Facades with shops (the scene's seed), as both modes' builders take them.
FacadeOptions shop_facades(const Scene& s) {
    FacadeOptions facades;
    facades.seed = s.header.seed;
    facades.shop_probability = 0.5;
    return facades;
}

// A small street corner: towers of several sizes, an L-shaped block, a courtyard building,
// a floating part, a road, a joint, sidewalks.
Scene test_scene() {
    Scene s;
    s.header.seed = 3;
    s.buildings.push_back(box_building(1, {0, 0}, {20, 14}, 31));
    s.buildings.push_back(box_building(2, {30, -5}, {42, 25}, 64));
    s.buildings.push_back(box_building(3, {-30, 5}, {-18, 9}, 7));  // narrow, low
    Building l;
    l.osm = {OsmType::Way, 4};
    l.outer = {{0, 30}, {25, 30}, {25, 38}, {9, 38}, {9, 55}, {0, 55}};
    l.height = 18;
    l.levels = 6;
    s.buildings.push_back(l);
    Building court = box_building(5, {-40, 30}, {-10, 60}, 24);
    court.holes.push_back({{-30, 40}, {-30, 50}, {-20, 50}, {-20, 40}});  // clockwise
    s.buildings.push_back(court);
    s.buildings.push_back(box_building(6, {50, 0}, {60, 10}, 20, 9));  // floating part
    RoadEdge west, east;  // trimmed to the joint between them, as osmparse does
    west.quad = {{-50, 20}, {-5, 20}, {-5, 27}, {-50, 27}};
    east.quad = {{5, 20}, {70, 20}, {70, 27}, {5, 27}};
    s.roads.push_back(west);
    s.roads.push_back(east);
    Joint joint;
    joint.polygon = {{-5, 20}, {5, 20}, {5, 27}, {-5, 27}};
    s.joints.push_back(joint);
    Sidewalk walk;
    walk.polygon = {{-50, 17}, {70, 17}, {70, 20}, {-50, 20}};
    s.sidewalks.push_back(walk);
    set_ground(s, {-60, -20}, {80, 70});
    return s;
}

double uniform(Rng& rng, double lo, double hi) { return lo + (hi - lo) * rng.next_double(); }

}  // namespace

TEST(ProceduralGeometry, SameHitsAsStoredTriangles) {
    const Scene scene = test_scene();
    const FacadeOptions facades = shop_facades(scene);
    auto stored = build_render_scene(scene, GeometryModes::all(GeometryMode::Stored), facades);
    auto procedural = build_render_scene(scene, GeometryModes::all(GeometryMode::Procedural), facades);

    Rng rng(5);
    int rays = 0, hits = 0, mismatches = 0;
    std::string first;
    for (int i = 0; i < 40000; ++i) {
        Ray ray;
        // From the street and from above, towards the buildings; some rays start on the far
        // side so that courtyards, rooms and undersides are seen too.
        ray.origin = {uniform(rng, -70, 90), uniform(rng, -30, 80), uniform(rng, 0.5, 90)};
        Vec3 target{uniform(rng, -45, 65), uniform(rng, -8, 62), uniform(rng, 0, 66)};
        ray.direction = normalize(target - ray.origin);
        Hit a, b;
        bool ha = stored->intersect(ray, a), hb = procedural->intersect(ray, b);
        bool oa = stored->occluded(ray), ob = procedural->occluded(ray);
        ++rays;
        std::string problem;
        if (ha != hb) problem = "hit/miss";
        else if (oa != ob) problem = "occlusion";
        else if (ha) {
            ++hits;
            if (a.kind != b.kind || a.object != b.object) problem = "object";
            else if (a.material != b.material) problem = "material " + std::to_string(a.material) + " vs " + std::to_string(b.material);
            else if (std::abs(a.t - b.t) > 1e-3 * std::max(1.0, a.t)) problem = "distance";
            else if (length(a.geometric_normal - b.geometric_normal) > 1e-3) problem = "normal";
        }
        if (!problem.empty()) {
            ++mismatches;
            if (first.empty()) first = problem;
        }
    }
    // Float rounding at shared edges may send a rare ray to the neighbouring surface.
    EXPECT_LE(mismatches, rays / 1000) << "first mismatch: " << first;
    EXPECT_GT(hits, rays / 2);
}

TEST(ProceduralGeometry, ProceduralBuildingsAreTiny) {
    const Scene scene = test_scene();
    FacadeOptions facades;
    auto procedural = build_procedural_buildings(scene, facades);
    TriangleMesh stored = build_stored_buildings(scene, facades);
    // One primitive per wall, roof and underside; the stored mesh has every window.
    size_t walls = 0;
    for (const Building& b : scene.buildings) walls += building_wall_count(b);
    EXPECT_EQ(procedural->wall_count(), walls);
    EXPECT_EQ(procedural->polygon_count(), scene.buildings.size() + 1);
    EXPECT_GT(stored.triangle_count(), 50 * procedural->primitive_count());
    EXPECT_LT(procedural->buffer_bytes() * 20, stored.bytes());
}

// A building of many courtyards (more than BuildingWalls keeps inline, some holes wound the
// wrong way): each wall is the ring edge a walk over the rings finds, with the building on its
// left, and rays from above find the same roof or courtyard floor in both modes (the procedural
// roof tests a point against the holes of a box tree, not each hole in turn).
TEST(ProceduralGeometry, ManyCourtyardsSameWallsAndHitsAsAWalkOverTheRings) {
    Scene scene;
    Building b = box_building(1, {-61, -61}, {61, 61}, 12);
    for (int i = 0; i < 1600; ++i) {
        const double x = -60 + 3.0 * (i % 40) + 1, y = -60 + 3.0 * (i / 40) + 1;
        b.holes.push_back({{x, y}, {x, y + 1}, {x + 1, y + 1}, {x + 1, y}});
        if (i % 7 == 0) std::reverse(b.holes.back().begin(), b.holes.back().end());
    }
    scene.buildings.push_back(b);
    scene.ground.min = {-100, -100};
    scene.ground.max = {100, 100};
    const BuildingWalls walls(b);
    ASSERT_EQ(walls.count(), 4u * 1601);
    size_t index = 0;
    for (size_t r = 0; r <= b.holes.size(); ++r) {
        const Ring& ring = r == 0 ? b.outer : b.holes[r - 1];
        for (size_t k = 0; k < ring.size(); ++k, ++index) {
            Vec2 p, q;
            walls.wall(index, &p, &q);
            const bool edge_of_ring =
                std::find(ring.begin(), ring.end(), p) != ring.end() && std::find(ring.begin(), ring.end(), q) != ring.end();
            ASSERT_TRUE(edge_of_ring) << "wall " << index;
            const Vec2 centre = r == 0 ? Vec2{0, 0} : (ring[0] + ring[2]) * 0.5;
            // The building on the left: inside the outer ring, outside each courtyard.
            EXPECT_EQ(cross(q - p, centre - p) > 0, r == 0) << "wall " << index;
            EXPECT_EQ(walls.input(index).wall_index, index);
        }
    }
    auto stored = build_render_scene(scene, GeometryModes::all(GeometryMode::Stored));
    auto procedural = build_render_scene(scene, GeometryModes::all(GeometryMode::Procedural));
    Rng rng(9);
    int roof = 0, mismatches = 0;
    for (int i = 0; i < 20000; ++i) {
        Ray ray;
        ray.origin = {uniform(rng, -62, 62), uniform(rng, -62, 62), 40};
        ray.direction = normalize(Vec3{uniform(rng, -0.05, 0.05), uniform(rng, -0.05, 0.05), -1});
        Hit a, h;
        const bool ha = stored->intersect(ray, a), hb = procedural->intersect(ray, h);
        if (ha != hb || a.kind != h.kind || std::abs(a.t - h.t) > 1e-3 * std::max(1.0, a.t)) ++mismatches;
        if (ha && a.kind == ObjectKind::Building && a.geometric_normal.z > 0.5) ++roof;
    }
    EXPECT_LE(mismatches, 20);   // rounding at shared edges
    EXPECT_GT(roof, 20000 / 2);  // most of the footprint is roof; 1/9 is courtyards
    EXPECT_LT(roof, 20000 * 19 / 20);
}

// The procedural builder makes runs of buildings side by side and joins them: buildings far
// down the list (windows, courtyards in a hole tree, a floating part, a gabled roof) keep their
// own surfaces once joined after thousands of others, as the stored builder (one pass) makes them.
TEST(ProceduralGeometry, BuildingsLateInALongListKeepTheirSurfaces) {
    Scene scene;
    scene.header.seed = 11;
    for (int i = 0; i < 2500; ++i) {
        const Vec2 at{-2000.0 + 40 * (i % 100), -2000.0 + 40 * (i / 100)};
        scene.buildings.push_back(box_building(i + 1, at, at + Vec2{12, 9}, 6 + i % 20));
    }
    auto courtyards = [](int64_t id, Vec2 at) {
        Building court = box_building(id, at, at + Vec2{61, 61}, 21);
        for (int i = 0; i < 36; ++i) {
            const Vec2 corner = at + Vec2{3.0 + 9.0 * (i % 6), 3.0 + 9.0 * (i / 6)};
            court.holes.push_back({corner, corner + Vec2{0, 4}, corner + Vec2{4, 4}, corner + Vec2{4, 0}});
        }
        return court;
    };
    scene.buildings[0] = courtyards(1, {-1000, -1000});  // a hole tree before the one in view
    scene.buildings.push_back(courtyards(9001, {0, 0}));
    scene.buildings.push_back(box_building(9002, {70, 0}, {82, 12}, 30, 12));  // floating part
    Building gabled = box_building(9003, {90, 0}, {104, 10}, 14);
    gabled.roof_shape = RoofShape::Gabled;
    gabled.roof_height = 4;  // walls to 10 m, the ridge along x at y = 5, 14 m (heights over the base)
    gabled.roof_faces = {{{{90, 0, 10}, {104, 0, 10}, {104, 5, 14}, {90, 5, 14}}},
                         {{{104, 10, 10}, {90, 10, 10}, {90, 5, 14}, {104, 5, 14}}},
                         {{{104, 0, 10}, {104, 10, 10}, {104, 5, 14}}, RoofFaceKind::Gable},
                         {{{90, 10, 10}, {90, 0, 10}, {90, 5, 14}}, RoofFaceKind::Gable}};
    scene.buildings.push_back(gabled);
    set_ground(scene, {-2100, -2100}, {2100, 2100});
    const FacadeOptions facades = shop_facades(scene);
    auto stored = build_render_scene(scene, GeometryModes::all(GeometryMode::Stored), facades);
    auto procedural = build_render_scene(scene, GeometryModes::all(GeometryMode::Procedural), facades);
    Rng rng(13);
    int late = 0, mismatches = 0;
    for (int i = 0; i < 20000; ++i) {
        Ray ray;
        ray.origin = {uniform(rng, -30, 130), uniform(rng, -40, 100), uniform(rng, 1, 60)};
        const Vec3 target{uniform(rng, 0, 104), uniform(rng, 0, 61), uniform(rng, 0, 30)};
        ray.direction = normalize(target - ray.origin);
        Hit a, b;
        const bool ha = stored->intersect(ray, a), hb = procedural->intersect(ray, b);
        if (ha != hb || a.kind != b.kind || a.object != b.object || a.material != b.material ||
            std::abs(a.t - b.t) > 1e-3 * std::max(1.0, a.t))
            ++mismatches;
        if (ha && a.kind == ObjectKind::Building && a.object >= 2500) ++late;
    }
    EXPECT_LE(mismatches, 20);  // rounding at shared edges
    EXPECT_GT(late, 20000 / 4);
}

// Coplanar overlapping surfaces (two road quads over each other, as near-parallel roads give):
// the same distance from both, and the lower primitive wins whatever order the BVH visits them
// in, so a change elsewhere in the scene does not flip which one is seen.
TEST(ProceduralGeometry, CoplanarOverlapGoesToTheLowerPrimitiveWhateverTheBvhOrder) {
    auto geometry = std::make_unique<ProceduralGeometry>(ObjectKind::Road, ProceduralGeometry::SurfaceMaterials{});
    constexpr int kPairs = 400;
    // Pair k: square k (primitive k) and its copy (primitive kPairs + k), far apart in the
    // primitive order so the BVH holds them in different leaves.
    auto square = [](int k) {
        const Vec2 c{(k % 20) * 10.0, (k / 20) * 10.0};
        return Ring{c, c + Vec2{8, 0}, c + Vec2{8, 8}, c + Vec2{0, 8}};
    };
    for (int copy = 0; copy < 2; ++copy)
        for (int k = 0; k < kPairs; ++k) geometry->add_polygon(static_cast<uint32_t>(copy * kPairs + k), square(k), {}, 0, 1);
    RenderScene scene;
    scene.add(std::move(geometry));
    scene.commit();
    Rng rng(5);
    int hits = 0;
    for (int i = 0; i < 4000; ++i) {
        const Vec3 target{rng.next_double() * 200, rng.next_double() * 200, 0};
        const Vec3 origin{rng.next_double() * 400 - 100, rng.next_double() * 400 - 100, 5 + rng.next_double() * 100};
        Ray ray;
        ray.origin = origin;
        ray.direction = normalize(target - origin);
        Hit hit;
        if (!scene.intersect(ray, hit)) continue;
        ++hits;
        ASSERT_LT(hit.object, static_cast<uint32_t>(kPairs)) << "ray " << i;
    }
    EXPECT_GT(hits, 2000);
}
