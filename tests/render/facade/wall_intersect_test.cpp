// The analytic wall intersector against brute force over the triangulated wall, and the facade
// rules' determinism and plain-wall cases.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "common/rng.h"
#include "render/facade/facade.h"
#include "render/facade/facade_mesh.h"
#include "render/facade/wall_intersect.h"

using namespace citygen;

namespace {

struct BruteHit {
    double t = std::numeric_limits<double>::infinity();
    Vec3 normal;
    FacadeSurface surface = FacadeSurface::Wall;
};

// Moller-Trumbore in double, both sides, edges inclusive (with a 1e-12 allowance for rounding),
// tmin <= t <= tmax. Returns every
// triangle hit at the nearest distance: a ray through an edge shared by two rectangles hits
// both, and either is a right answer.
std::vector<BruteHit> brute_intersect(const FacadeMesh& mesh, Vec3 o, Vec3 d, double tmin, double tmax) {
    const double kEdge = 1e-12;
    std::vector<BruteHit> hits;
    for (size_t i = 0; i < mesh.triangles.size(); ++i) {
        const auto& tri = mesh.triangles[i];
        Vec3 p0 = mesh.vertices[tri[0]], p1 = mesh.vertices[tri[1]], p2 = mesh.vertices[tri[2]];
        Vec3 e1 = p1 - p0, e2 = p2 - p0;
        Vec3 pv = cross(d, e2);
        double det = dot(e1, pv);
        if (det == 0) continue;
        double inv = 1.0 / det;
        Vec3 tv = o - p0;
        double b1 = dot(tv, pv) * inv;
        if (b1 < -kEdge || b1 > 1 + kEdge) continue;
        Vec3 qv = cross(tv, e1);
        double b2 = dot(d, qv) * inv;
        if (b2 < -kEdge || b1 + b2 > 1 + kEdge) continue;
        double t = dot(e2, qv) * inv;
        if (t < tmin || t > tmax) continue;
        hits.push_back({t, normalize(cross(e1, e2)), mesh.surfaces[i]});
    }
    double nearest = std::numeric_limits<double>::infinity();
    for (const BruteHit& h : hits) nearest = std::min(nearest, h.t);
    std::vector<BruteHit> tied;
    for (const BruteHit& h : hits)
        if (h.t <= nearest + 1e-9 * std::max(1.0, nearest)) tied.push_back(h);
    return tied;
}

double uniform(Rng& rng, double lo, double hi) { return lo + (hi - lo) * rng.next_double(); }

Vec3 random_unit(Rng& rng) {
    for (;;) {
        Vec3 v{uniform(rng, -1, 1), uniform(rng, -1, 1), uniform(rng, -1, 1)};
        double l = length(v);
        if (l > 0.05 && l <= 1) return v * (1.0 / l);
    }
}

// A wall to test: its layout, where it stands, and its triangles.
struct TestWall {
    WallLayout layout;
    WallFrame frame;
    FacadeMesh mesh;
};

TestWall make_test_wall(uint64_t seed, uint64_t key, double length, double height, double bottom, bool world) {
    FacadeOptions options;
    options.seed = seed;
    options.shop_probability = 0.5;
    WallInput input;
    input.building_key = key;
    input.wall_index = static_cast<uint32_t>(key % 7);
    input.length = length;
    input.height = height;
    input.bottom_z = bottom;
    TestWall wall;
    wall.layout = make_wall_layout(options, input);
    if (world) {
        Rng rng(seed, key);
        Vec2 a{uniform(rng, -3000, 3000), uniform(rng, -3000, 3000)};
        double angle = uniform(rng, 0, 6.283185307179586);
        wall.frame = wall_frame(a, a + Vec2{std::cos(angle), std::sin(angle)} * length, bottom);
    }
    append_wall_mesh(wall.layout, wall.frame, wall.mesh);
    return wall;
}

struct Comparison {
    int rays = 0, hits = 0, mismatches = 0;
    std::string first_problem;
};

void compare_ray(const TestWall& wall, Vec3 o, Vec3 d, double tmax, Comparison* c) {
    ++c->rays;
    std::vector<BruteHit> tied = brute_intersect(wall.mesh, o, d, 0.0, tmax);
    bool brute = !tied.empty();
    WallHit got;
    bool analytic = intersect_wall(wall.layout, wall.frame, o, d, 0.0, tmax, &got);
    bool occluded = wall_occluded(wall.layout, wall.frame, o, d, 0.0, tmax);
    std::string problem;
    if (brute != analytic) {
        problem = std::string("hit/miss differ: brute ") +
                  (brute ? "hit " + std::string(to_string(tied[0].surface)) + " t=" + std::to_string(tied[0].t)
                         : "miss") +
                  ", analytic " + (analytic ? "hit " + std::string(to_string(got.surface)) : "miss");
    } else if (occluded != brute) {
        problem = "occlusion differs from brute force";
    } else if (brute) {
        ++c->hits;
        const BruteHit& expected = tied[0];
        double tolerance = 1e-4 * std::max(1.0, expected.t);
        bool same_surface = false, same_normal = false;
        for (const BruteHit& h : tied) {
            if (h.surface != got.surface) continue;
            same_surface = true;
            same_normal = same_normal || length(h.normal - got.normal) < 1e-6;
        }
        if (std::abs(expected.t - got.t) > tolerance)
            problem = "t differs: " + std::to_string(expected.t) + " vs " + std::to_string(got.t);
        else if (!same_surface)
            problem = std::string("surface differs: ") + to_string(expected.surface) + " vs " + to_string(got.surface);
        else if (!same_normal)
            problem = "normal differs";
    }
    if (!problem.empty()) {
        ++c->mismatches;
        if (c->first_problem.empty()) {
            Vec3 lo = wall.frame.point_to_local(o), ld = wall.frame.direction_to_local(d);
            c->first_problem = problem + " (local origin " + std::to_string(lo.x) + "," + std::to_string(lo.y) + "," +
                               std::to_string(lo.z) + " dir " + std::to_string(ld.x) + "," + std::to_string(ld.y) +
                               "," + std::to_string(ld.z) + ")";
        }
    }
}

// A few wall shapes: plain, small, tall, with and without balconies and shops.
std::vector<TestWall> test_walls(bool world) {
    std::vector<TestWall> walls;
    const double sizes[][2] = {{1.2, 10}, {12, 2.0}, {7, 7}, {15, 31}, {9.5, 18}, {23, 12}, {4, 50}};
    uint64_t key = 1;
    for (auto size : sizes)
        for (int variant = 0; variant < 4; ++variant)
            walls.push_back(make_test_wall(77, key++, size[0], size[1], variant == 3 ? 6.0 : 0.0, world));
    return walls;
}

Vec3 local_to_world(const TestWall& wall, Vec3 p) { return wall.frame.to_world(p.x, p.y, p.z); }

}  // namespace

TEST(FacadeRules, SameInputsSameLayout) {
    FacadeOptions options;
    options.seed = 5;
    WallInput input{1234, 3, 17.5, 0.0, 24.0, 0};
    WallLayout a = make_wall_layout(options, input), b = make_wall_layout(options, input);
    ASSERT_FALSE(a.plain());
    EXPECT_EQ(a.floors, b.floors);
    EXPECT_EQ(a.slots, b.slots);
    EXPECT_EQ(a.slot_width, b.slot_width);
    EXPECT_EQ(a.floor_height, b.floor_height);
    EXPECT_EQ(a.recess, b.recess);
    EXPECT_EQ(a.balconies, b.balconies);
    EXPECT_EQ(a.shop, b.shop);
    TestWall wa = make_test_wall(5, 99, 17.5, 24.0, 0, true), wb = make_test_wall(5, 99, 17.5, 24.0, 0, true);
    ASSERT_EQ(wa.mesh.vertices.size(), wb.mesh.vertices.size());
    for (size_t i = 0; i < wa.mesh.vertices.size(); ++i) ASSERT_EQ(length(wa.mesh.vertices[i] - wb.mesh.vertices[i]), 0.0);
}

TEST(FacadeRules, SeedsAndBuildingsVary) {
    // Over many buildings, seeds change the style and both styles and shops occur.
    int differ = 0, with_balconies = 0, with_shop = 0, total = 200;
    for (uint64_t key = 0; key < static_cast<uint64_t>(total); ++key) {
        WallInput input{key, 0, 20.0, 0.0, 30.0, 0};
        FacadeOptions s1, s2;
        s1.seed = 1;
        s2.seed = 2;
        WallLayout a = make_wall_layout(s1, input), b = make_wall_layout(s2, input);
        if (a.slot_width != b.slot_width || a.floor_height != b.floor_height) ++differ;
        with_balconies += a.balconies;
        with_shop += a.shop;
    }
    EXPECT_GT(differ, total * 9 / 10);
    EXPECT_GT(with_balconies, total / 10);
    EXPECT_LT(with_balconies, total / 2);
    EXPECT_GT(with_shop, total / 10);  // default probability 0.3
    EXPECT_LT(with_shop, total / 2);
}

TEST(FacadeRules, ShopProbabilityAndFloatingParts) {
    for (uint64_t key = 0; key < 50; ++key) {
        WallInput ground{key, 1, 20.0, 0.0, 30.0, 0};
        WallInput raised = ground;
        raised.bottom_z = 10;
        FacadeOptions never, always;
        never.shop_probability = 0;
        always.shop_probability = 1;
        EXPECT_FALSE(make_wall_layout(never, ground).shop);
        WallLayout shop = make_wall_layout(always, ground);
        EXPECT_EQ(shop.shop, shop.floor_height >= 2.8);
        EXPECT_FALSE(make_wall_layout(always, raised).shop);  // a building part above the street
    }
}

TEST(FacadeRules, TaggedLevelsSetFloorHeight) {
    WallInput input{42, 0, 20.0, 0.0, 3.5 * 10 + 1.5, 10};
    WallLayout layout = make_wall_layout(FacadeOptions{}, input);
    ASSERT_FALSE(layout.plain());
    // Margins take up to 1.6 m, so 9 or 10 floors of about 3.5 m fit.
    EXPECT_GE(layout.floors, 9);
    EXPECT_LE(layout.floors, 10);
}

TEST(FacadeRules, ShortOrNarrowWallsStayPlain) {
    for (uint64_t key = 0; key < 50; ++key) {
        WallLayout narrow = make_wall_layout(FacadeOptions{}, WallInput{key, 0, 1.5, 0.0, 30.0, 0});
        WallLayout low = make_wall_layout(FacadeOptions{}, WallInput{key, 0, 30.0, 0.0, 2.0, 0});
        EXPECT_TRUE(narrow.plain());
        EXPECT_TRUE(low.plain());
        EXPECT_EQ(wall_triangle_count(narrow), 2u);
        EXPECT_EQ(narrow.w_min(), 0.0);
        EXPECT_EQ(narrow.w_max(), 0.0);
    }
}

TEST(FacadeRules, CellGeometryStaysInsideItsCellAndSlab) {
    for (uint64_t key = 0; key < 40; ++key) {
        TestWall wall = make_test_wall(3, key, 5 + key * 0.7, 3 + key * 1.3, 0, false);
        const WallLayout& l = wall.layout;
        FacadeRect rects[kMaxCellRects];
        for (int f = 0; f < l.floors; ++f) {
            for (int s = 0; s < l.slots; ++s) {
                int n = cell_rects(l, f, s, rects);
                ASSERT_LE(n, kMaxCellRects);
                double cu0 = l.grid_u0 + s * l.slot_width, cv0 = l.grid_v0 + f * l.floor_height;
                for (int i = 0; i < n; ++i) {
                    const FacadeRect& r = rects[i];
                    double lo[3], hi[3];
                    int a = r.axis == 0 ? 1 : 0, b = r.axis == 2 ? 1 : 2;
                    lo[r.axis] = hi[r.axis] = r.at;
                    lo[a] = r.a0; hi[a] = r.a1;
                    lo[b] = r.b0; hi[b] = r.b1;
                    const double eps = 1e-9;
                    EXPECT_LT(lo[a], hi[a]);
                    EXPECT_LT(lo[b], hi[b]);
                    EXPECT_GE(lo[0], cu0 - eps);
                    EXPECT_LE(hi[0], cu0 + l.slot_width + eps);
                    EXPECT_GE(lo[1], cv0 - eps);
                    EXPECT_LE(hi[1], cv0 + l.floor_height + eps);
                    EXPECT_GE(lo[2], l.w_min() - eps);
                    EXPECT_LE(hi[2], l.w_max() + eps);
                }
            }
        }
    }
}

TEST(WallIntersect, MatchesTriangulatedWallForRandomRays) {
    Comparison c;
    Rng rng(2024);
    for (const TestWall& wall : test_walls(true)) {
        const double L = wall.layout.length, H = wall.layout.height;
        for (int i = 0; i < 1500; ++i) {
            // From in front of the wall towards a point on or near it.
            Vec3 from{uniform(rng, -5, L + 5), uniform(rng, -5, H + 5), uniform(rng, -25, -0.5)};
            Vec3 to{uniform(rng, -1, L + 1), uniform(rng, -1, H + 1), uniform(rng, -1.5, 3)};
            Vec3 o = local_to_world(wall, from);
            Vec3 d = normalize(local_to_world(wall, to) - o);
            compare_ray(wall, o, d, i % 5 == 0 ? uniform(rng, 0, 30) : 1e30, &c);
            // From anywhere around or inside the slab, in any direction.
            Vec3 inside{uniform(rng, -2, L + 2), uniform(rng, -2, H + 2), uniform(rng, -2, 5)};
            compare_ray(wall, local_to_world(wall, inside), random_unit(rng), 1e30, &c);
        }
    }
    EXPECT_EQ(c.mismatches, 0) << c.first_problem;
    EXPECT_GT(c.hits, c.rays / 3);
}

TEST(WallIntersect, MatchesTriangulatedWallForGrazingRays) {
    Comparison c;
    Rng rng(7);
    for (const TestWall& wall : test_walls(true)) {
        const double L = wall.layout.length, H = wall.layout.height;
        for (int i = 0; i < 1500; ++i) {
            Vec3 from{uniform(rng, -5, L + 5), uniform(rng, -1, H + 1), uniform(rng, -2, -1e-3)};
            double angle = uniform(rng, 0, 6.283185307179586);
            double slope = std::pow(10.0, uniform(rng, -5, -1)) * (rng.next_double() < 0.8 ? 1 : -1);
            Vec3 dir = normalize(Vec3{std::cos(angle), std::sin(angle), slope});
            compare_ray(wall, local_to_world(wall, from), wall.frame.direction_to_world(dir), 1e30, &c);
        }
    }
    EXPECT_EQ(c.mismatches, 0) << c.first_problem;
    EXPECT_GT(c.hits, c.rays / 50);
}

TEST(WallIntersect, MatchesTriangulatedWallFromInsideARecess) {
    Comparison c;
    Rng rng(11);
    for (const TestWall& wall : test_walls(true)) {
        const WallLayout& l = wall.layout;
        if (l.plain()) continue;
        FacadeRect rects[kMaxCellRects];
        for (int i = 0; i < 600; ++i) {
            int f = static_cast<int>(rng.next_u32() % l.floors), s = static_cast<int>(rng.next_u32() % l.slots);
            int layer_end[kCellLayers];
            cell_rects(l, f, s, rects, layer_end);
            const FacadeRect& pane = rects[layer_end[2]];  // first of the pane layer
            ASSERT_EQ(pane.axis, 2);
            ASSERT_TRUE(pane.surface == FacadeSurface::Glass || pane.surface == FacadeSurface::BalconyDoor ||
                        pane.surface == FacadeSurface::ShopWindow);
            Vec3 from{uniform(rng, pane.a0, pane.a1), uniform(rng, pane.b0, pane.b1), uniform(rng, 1e-3, pane.at - 1e-3)};
            compare_ray(wall, local_to_world(wall, from), random_unit(rng), 1e30, &c);
        }
    }
    EXPECT_EQ(c.mismatches, 0) << c.first_problem;
    EXPECT_GT(c.hits, c.rays / 2);  // a recess is closed on every side but the street
}

TEST(WallIntersect, MatchesTriangulatedWallAlongTheWallPlane) {
    // Rays with no component across the wall, in the exact wall-local frame so that "along the
    // plane" is exact: on the facade plane, in front (balconies), in the recess and in the rooms.
    Comparison c;
    Rng rng(13);
    for (const TestWall& wall : test_walls(false)) {
        const WallLayout& l = wall.layout;
        const double depths[] = {0.0, -1e-3, -0.5 * l.balcony_depth, 0.5 * l.recess, l.recess + 0.5 * l.room_depth};
        for (double w : depths) {
            for (int i = 0; i < 200; ++i) {
                Vec3 from{uniform(rng, -3, l.length + 3), uniform(rng, -1, l.height + 1), w};
                double angle = uniform(rng, 0, 6.283185307179586);
                compare_ray(wall, from, Vec3{std::cos(angle), std::sin(angle), 0}, 1e30, &c);
            }
        }
    }
    EXPECT_EQ(c.mismatches, 0) << c.first_problem;
    EXPECT_GT(c.hits, c.rays / 10);
}

TEST(WallIntersect, CostGrowsWithCellsCrossedNotWallSize) {
    // A huge facade: a ray straight at it visits one cell; a ray along a row visits that row.
    TestWall wall = make_test_wall(1, 5, 300, 200, 0, false);
    ASSERT_GT(wall.layout.floors * wall.layout.slots, 3000);
    WallIntersectStats& stats = wall_intersect_stats();
    stats = {};
    WallHit hit;
    ASSERT_TRUE(intersect_wall(wall.layout, wall.frame, Vec3{150.3, 100.2, -10}, Vec3{0, 0, 1}, 0, 1e30, &hit));
    EXPECT_EQ(stats.cells, 1u);
    stats = {};
    // Inside the solid wall (between the facade plane and the panes) just above a floor's
    // bottom, along a whole row of cells: nothing there to hit, every slot visited once.
    Vec3 o{-1, wall.layout.grid_v0 + wall.layout.floor_height + 0.1, 0.5 * wall.layout.recess};
    EXPECT_FALSE(intersect_wall(wall.layout, wall.frame, o, Vec3{1, 0, 0}, 0, 1e30, &hit));
    EXPECT_EQ(stats.cells, static_cast<uint64_t>(wall.layout.slots));
}

TEST(FacadeRules, WallsHaveTheBuildingOnTheirLeftWhateverTheRingOrientation) {
    Building b;
    b.outer = {{0, 0}, {10, 0}, {10, 8}, {4, 8}, {4, 20}, {0, 20}};  // L shape, CCW
    b.holes.push_back({{1, 1}, {1, 3}, {3, 3}, {3, 1}});               // CW courtyard
    b.height = 12;
    Building reversed = b;
    std::reverse(reversed.outer.begin(), reversed.outer.end());
    std::reverse(reversed.holes[0].begin(), reversed.holes[0].end());
    ASSERT_EQ(building_wall_count(b), 10u);
    for (const Building* building : {&b, &reversed}) {
        for (size_t i = 0; i < building_wall_count(*building); ++i) {
            Vec2 p, q;
            building_wall(*building, i, &p, &q);
            WallFrame frame = wall_frame(p, q, 0);
            Vec3 inside = frame.to_world(0.5 * length(q - p), 1, 0.05);  // just behind the facade
            Vec3 outside = frame.to_world(0.5 * length(q - p), 1, -0.05);
            auto in_building = [&](Vec3 x) {
                Vec2 xy{x.x, x.y};
                return point_in_ring(xy, building->outer) && !point_in_ring(xy, building->holes[0]);
            };
            EXPECT_TRUE(in_building(inside)) << "wall " << i;
            EXPECT_FALSE(in_building(outside)) << "wall " << i;
        }
    }
}

TEST(FacadeRules, WallsOfBuildingsWithManyCourtyardsHaveTheBuildingOnTheirLeft) {
    // BuildingWalls keeps the orientation of the first 64 rings and finds the others again.
    Building b;
    b.outer = {{0, 0}, {100, 0}, {100, 100}, {0, 100}};
    b.height = 12;
    for (int h = 0; h < 70; ++h) {
        const double x = 5 + 10 * (h % 9), y = 5 + 10 * (h / 9);
        Ring hole{{x, y}, {x, y + 2}, {x + 2, y + 2}, {x + 2, y}};  // clockwise
        if (h % 3 == 0) std::reverse(hole.begin(), hole.end());
        b.holes.push_back(hole);
    }
    auto in_building = [&](Vec3 x) {
        const Vec2 xy{x.x, x.y};
        if (!point_in_ring(xy, b.outer)) return false;
        for (const Ring& hole : b.holes)
            if (point_in_ring(xy, hole)) return false;
        return true;
    };
    const BuildingWalls walls(b);
    ASSERT_EQ(walls.count(), 4u + 70 * 4);
    for (size_t i = 0; i < walls.count(); ++i) {
        Vec2 p, q;
        walls.wall(i, &p, &q);
        const WallFrame frame = wall_frame(p, q, 0);
        EXPECT_TRUE(in_building(frame.to_world(0.5 * length(q - p), 1, 0.05))) << "wall " << i;
        EXPECT_FALSE(in_building(frame.to_world(0.5 * length(q - p), 1, -0.05))) << "wall " << i;
    }
}

TEST(FacadeRules, RoomBoxesStayInsideFootprintsWithAcuteCorners) {
    // An equilateral triangle (60 degree corners) and a parallelogram (50 degree corners): the
    // neighbouring wall runs in behind the end cells, so the rooms there must be shallower.
    std::vector<Ring> footprints = {
        {{0, 0}, {30, 0}, {15, 25.98}},
        {{0, 0}, {30, 0}, {30 + 19.28, 22.98}, {19.28, 22.98}},
    };
    int deep_rooms_checked = 0;
    for (uint64_t seed = 0; seed < 20; ++seed) {
        for (const Ring& ring : footprints) {
            Building b;
            b.osm = {OsmType::Way, static_cast<int64_t>(seed)};
            b.outer = ring;
            b.height = 30;
            FacadeOptions options;
            options.seed = seed;
            for (size_t i = 0; i < building_wall_count(b); ++i) {
                Vec2 p, q;
                building_wall(b, i, &p, &q);
                const WallLayout l = make_wall_layout(options, building_wall_input(b, i));
                const WallFrame frame = wall_frame(p, q, 0);
                if (l.plain()) continue;
                for (int s = 0; s < l.slots; ++s) {
                    const double u0 = l.grid_u0 + s * l.slot_width + WallLayout::kRoomInset;
                    const double u1 = u0 + l.slot_width - 2 * WallLayout::kRoomInset;
                    for (double u : {u0, u1}) {
                        Vec3 corner = frame.to_world(u, 1, l.recess + l.room_depth);
                        EXPECT_TRUE(point_in_ring({corner.x, corner.y}, b.outer))
                            << "seed " << seed << " wall " << i << " slot " << s;
                    }
                }
                deep_rooms_checked += l.room_depth > 0.5;
            }
        }
    }
    EXPECT_GT(deep_rooms_checked, 20);
}
