// The building index (polygon_overlap.h): every query visits each building whose box meets the
// query box exactly once, queries keep no state, so threads may share one index, and long rings
// answer contains() from their bands as from all their edges.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <thread>

#include "osmparse/polygons/exact_predicates.h"
#include "osmparse/polygons/polygon_overlap.h"
#include "tests/test_scenes.h"

using namespace citygen;
using namespace citygen::test;

namespace {

// Buildings from a few metres to a few hundred metres across (spanning one to many 50 m cells),
// and boxes to query, from a fixed seed.
struct Layout {
    std::vector<Building> buildings;
    std::vector<Box2> queries;
};

Layout random_layout() {
    std::mt19937 rng(12);
    std::uniform_real_distribution<double> where(-600, 600), size(1, 40), big(100, 400);
    Layout layout;
    for (int i = 0; i < 600; ++i) {
        const double x = where(rng), y = where(rng), w = i % 50 == 0 ? big(rng) : size(rng), h = size(rng);
        layout.buildings.push_back(box_building(x, y, x + w, y + h));
    }
    for (int i = 0; i < 300; ++i) {
        const double x = where(rng), y = where(rng), s = i % 3 == 0 ? 0 : big(rng) * (i % 2 ? 0.05 : 1);
        Box2 box;
        box.extend({x, y});
        box.extend({x + s, y + s});
        layout.queries.push_back(box);
    }
    return layout;
}

// Every building for each query, in the order the index visits them.
std::vector<std::vector<uint32_t>> visits(const BuildingIndex& index, const std::vector<Box2>& queries, size_t from,
                                          size_t step) {
    std::vector<std::vector<uint32_t>> out(queries.size());
    for (size_t q = from; q < queries.size(); q += step)
        index.for_each_near(queries[q], [&](uint32_t i) { out[q].push_back(i); });
    return out;
}

}  // namespace

TEST(BuildingIndex, VisitsEachBuildingWhoseBoxMeetsTheQueryOnce) {
    const Layout layout = random_layout();
    const BuildingIndex index(layout.buildings);
    const std::vector<std::vector<uint32_t>> found = visits(index, layout.queries, 0, 1);
    size_t nonempty = 0;
    for (size_t q = 0; q < layout.queries.size(); ++q) {
        std::vector<uint32_t> expected;
        for (uint32_t i = 0; i < layout.buildings.size(); ++i)
            if (bounds_of(layout.buildings[i].outer).overlaps(layout.queries[q])) expected.push_back(i);
        std::vector<uint32_t> got = found[q];
        std::sort(got.begin(), got.end());
        EXPECT_EQ(got, expected) << "query " << q;  // no building missed, none twice
        EXPECT_EQ(index.near(layout.queries[q]), expected);
        nonempty += !expected.empty();
    }
    EXPECT_GT(nonempty, 100u);  // the layout does exercise the index
}

TEST(BuildingIndex, ThreadsSharingAnIndexGetTheAnswersOfOne) {
    const Layout layout = random_layout();
    const BuildingIndex index(layout.buildings);
    const std::vector<std::vector<uint32_t>> alone = visits(index, layout.queries, 0, 1);
    // Two threads query the same index at once, each every other box, many times over.
    std::vector<std::vector<uint32_t>> shared(layout.queries.size());
    auto run = [&](size_t from) {
        for (int round = 0; round < 20; ++round) {
            std::vector<std::vector<uint32_t>> found = visits(index, layout.queries, from, 2);
            if (round == 0)
                for (size_t q = from; q < found.size(); q += 2) shared[q] = std::move(found[q]);
        }
    };
    std::thread other(run, 1);
    run(0);
    other.join();
    EXPECT_EQ(shared, alone);  // same buildings in the same order
}

TEST(BuildingIndex, BorrowedPolygonsAnswerLikeTheBuildingsTheyPointTo) {
    Layout layout = random_layout();
    // A courtyard in one building, so holes count too.
    layout.buildings[7].holes.push_back(Ring{{layout.buildings[7].outer[0] + Vec2(0.2, 0.2)},
                                             {layout.buildings[7].outer[0] + Vec2(0.2, 0.6)},
                                             {layout.buildings[7].outer[0] + Vec2(0.6, 0.6)},
                                             {layout.buildings[7].outer[0] + Vec2(0.6, 0.2)}});
    std::vector<PolygonRef> borrowed;
    for (const Building& b : layout.buildings) borrowed.push_back({&b.outer, &b.holes});
    const BuildingIndex of_buildings(layout.buildings), of_refs(borrowed);
    EXPECT_EQ(visits(of_refs, layout.queries, 0, 1), visits(of_buildings, layout.queries, 0, 1));
    size_t overlapping = 0;
    for (const Box2& q : layout.queries) {
        const Ring piece{q.min, {q.max.x, q.min.y}, q.max + Vec2(1, 1), {q.min.x, q.max.y}};
        double largest_b = 0, largest_r = 0;
        const double total = of_buildings.overlap(piece, &largest_b);
        EXPECT_EQ(of_refs.overlap(piece, &largest_r), total);
        EXPECT_EQ(largest_r, largest_b);
        EXPECT_EQ(of_refs.contains(q.min), of_buildings.contains(q.min));
        overlapping += total > 0;
    }
    EXPECT_GT(overlapping, 50u);
    for (uint32_t i = 0; i < layout.buildings.size(); ++i) EXPECT_EQ(of_refs.polygon(i).outer, &layout.buildings[i].outer);
    // A polygon without holes (a road quad) may leave them null.
    const Ring quad{{0, 0}, {10, 0}, {10, 10}, {0, 10}};
    const BuildingIndex of_quad(std::vector<PolygonRef>{{&quad}});
    EXPECT_DOUBLE_EQ(of_quad.overlap(Ring{{5, 5}, {15, 5}, {15, 15}, {5, 15}}), 25.0);
    EXPECT_TRUE(of_quad.contains({1, 1}));
}

// A coast-like ring of thousands of vertices (its edges sorted into bands of y for contains())
// with a long island as a hole, and an edge across the whole ring: contains() answers as the
// plain winding number does, at points on the vertices' own y values, between them and outside.
TEST(BuildingIndex, LongRingsAnswerAsTheWholeRingDoes) {
    std::mt19937 rng(5);
    std::uniform_real_distribution<double> wiggle(0.6, 1.0);
    auto star = [&](double radius, int n, Vec2 centre) {
        Ring ring;
        for (int i = 0; i < n; ++i) {
            const double a = 2 * kPi * i / n, r = radius * wiggle(rng);
            ring.push_back(centre + Vec2(r * std::cos(a), r * std::sin(a)));
        }
        return ring;
    };
    Building coast;
    coast.outer = star(1000, 4000, {0, 0});
    coast.outer.push_back({0, -1500});  // two edges reaching below the rest: every band in between
    coast.holes.push_back(star(200, 600, {300, 100}));
    ASSERT_GE(coast.holes[0].size(), RingBands::kMinVertices);
    const std::vector<Building> buildings{coast};
    const BuildingIndex index(buildings);
    std::vector<Vec2> points;
    std::uniform_real_distribution<double> where(-1600, 1600);
    for (int i = 0; i < 20000; ++i) points.push_back({where(rng), where(rng)});
    for (size_t i = 0; i < coast.outer.size(); i += 7) points.push_back({where(rng), coast.outer[i].y});
    for (const Vec2& v : coast.holes[0]) points.push_back({v.x + 0.5, v.y});
    size_t inside = 0;
    for (const Vec2& p : points) {
        const bool whole = exact_point_in_ring(p, coast.outer) && !exact_point_in_ring(p, coast.holes[0]);
        ASSERT_EQ(index.contains(p), whole) << p.x << "," << p.y;
        inside += whole;
    }
    EXPECT_GT(inside, 2000u);
    EXPECT_LT(inside, points.size() - 2000);
}
