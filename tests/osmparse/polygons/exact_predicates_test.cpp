// exact_predicates: the filtered predicates answer as CGAL's exact arithmetic does, on points
// that differ in their last bits, where the plain float evaluation gets them wrong.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "osmparse/polygons/cgal_footprint.h"
#include "osmparse/polygons/clean_footprint.h"
#include "osmparse/polygons/exact_predicates.h"
#include "osmparse/polygons/ring_is_simple.h"

using namespace citygen;

namespace {

int float_orientation(Vec2 a, Vec2 b, Vec2 c) {
    const double v = cross(b - a, c - a);
    return (v > 0) - (v < 0);
}

// p moved by i and j units in its last place.
Vec2 nudged(Vec2 p, int i, int j) {
    auto step = [](double v, int k) {
        for (; k > 0; --k) v = std::nextafter(v, std::numeric_limits<double>::infinity());
        for (; k < 0; ++k) v = std::nextafter(v, -std::numeric_limits<double>::infinity());
        return v;
    };
    return {step(p.x, i), step(p.y, j)};
}

constexpr int kNudges = 24;  // a 49 x 49 grid of last-bit moves round the point

}  // namespace

// Points on or next to the line through (0.5, 0.5) and (24, 24), the classic failure of the float
// orientation test: it answers wrong signs for some of them; the filtered test never does.
TEST(ExactPredicates, OrientationAgreesWithCgalWhereFloatFails) {
    const Vec2 a{0.5, 0.5}, b{24, 24};
    int float_wrong = 0, fallbacks_checked = 0;
    for (int i = -kNudges; i <= kNudges; ++i)
        for (int j = -kNudges; j <= kNudges; ++j) {
            const Vec2 p = nudged({12, 12}, i, j);
            const int exact = exact_detail::orientation_by_cgal(a, b, p);
            ASSERT_EQ(exact_orientation(a, b, p), exact) << i << " " << j;
            ASSERT_EQ(exact_orientation(b, p, a), exact);  // the same turn, another evaluation
            float_wrong += float_orientation(a, b, p) != exact;
            ++fallbacks_checked;
        }
    EXPECT_GT(float_wrong, 0) << "the grid no longer shows a float failure: the test proves nothing";
    EXPECT_EQ(exact_orientation({0, 0}, {1, 0}, {2, 0}), 0);
    EXPECT_EQ(exact_orientation({0, 0}, {1, 0}, {0, 1}), 1);
    EXPECT_EQ(exact_orientation({0, 0}, {0, 1}, {1, 0}), -1);
}

// A ring whose vertex q sits within a few units in the last place of a non-adjacent edge:
// simple only when q is strictly on the inner side. The pairwise test (rings of <= 32 points)
// must agree with CGAL's sweep on every one; the float segment test did not.
TEST(ExactPredicates, NearTouchingRingsAgreeWithTheSweep) {
    const Vec2 a{0.5, 0.5}, b{24, 24};
    int float_wrong = 0, simple = 0;
    for (int i = -kNudges; i <= kNudges; ++i)
        for (int j = -kNudges; j <= kNudges; ++j) {
            const Vec2 q = nudged({12, 12}, i, j);
            const Ring ring{a, b, {0, 30}, q, {-5, 10}};
            const bool sweep = ring_is_simple_sweep(ring);
            ASSERT_EQ(ring_is_simple(ring), sweep) << i << " " << j;
            simple += sweep;
            const bool float_touch = segments_intersect(a, b, {0, 30}, q) || segments_intersect(a, b, q, {-5, 10});
            float_wrong += float_touch == sweep;  // touching means not simple
        }
    EXPECT_GT(simple, 0);
    EXPECT_LT(simple, (2 * kNudges + 1) * (2 * kNudges + 1));
    EXPECT_GT(float_wrong, 0) << "the grid no longer shows a float failure: the test proves nothing";
}

// A hole whose corner q is within last bits of the outline's diagonal edge: kept exactly when
// it lies strictly inside (CGAL's validity check says so); every stored polygon is valid.
TEST(ExactPredicates, HoleContainmentIsExact) {
    const Ring outer{{0.5, 0.5}, {24, 24}, {0.5, 24}};
    int kept = 0, dropped = 0;
    for (int i = -kNudges; i <= kNudges; i += 3)
        for (int j = -kNudges; j <= kNudges; j += 3) {
            const Vec2 q = nudged({12, 12}, i, j);
            const Ring hole{q, {5, 15}, {10, 20}};  // clockwise, as a hole is stored
            ParseReport report;
            const auto polygons = clean_footprint(outer, {hole}, BuildingParams{}, report, ReportKind::Buildings);
            ASSERT_EQ(polygons.size(), 1u);
            for (const Footprint& f : polygons) ASSERT_TRUE(polygon_is_valid_exact(f.outer, f.holes));
            const bool inside = polygon_is_valid_exact(outer, {hole});
            ASSERT_EQ(polygons[0].holes.size(), inside ? 1u : 0u) << i << " " << j;
            (inside ? kept : dropped) += 1;
        }
    EXPECT_GT(kept, 0);
    EXPECT_GT(dropped, 0);
}

// A vertex exactly 1 cm (the tolerance, as a double) off the line through its neighbours is
// collinear and dropped; |cross| / length in float came out above the tolerance for some lengths.
TEST(ExactPredicates, CollinearAtTheToleranceIsExact) {
    int float_wrong = 0;
    for (int k = 1; k <= 400; ++k) {
        const double length = 1 + k * 0.37;
        const Vec2 a{0, 0}, b{length, 0}, p{length / 2, kFootprintTolerance};
        ASSERT_TRUE(exact_near_line(p, a, b, kFootprintTolerance)) << length;
        ASSERT_FALSE(exact_near_line(nudged(p, 0, 1), a, b, kFootprintTolerance)) << length;
        const double float_distance = std::fabs(cross(b - a, p - a)) / std::sqrt(dot(b - a, b - a));
        float_wrong += float_distance > kFootprintTolerance;
        // The clean-up drops the vertex: a rectangle with a 1 cm bump on its top edge.
        const Ring cleaned = remove_repeated_and_collinear({a, p, b, {length, -5}, {0, -5}});
        ASSERT_EQ(cleaned.size(), 4u) << length;
    }
    EXPECT_GT(float_wrong, 0) << "no length shows a float failure: the test proves nothing";
    EXPECT_TRUE(exact_within_distance({0, 0}, {kFootprintTolerance, 0}, kFootprintTolerance));
    EXPECT_FALSE(exact_within_distance({0, 0}, nudged({kFootprintTolerance, 0}, 1, 0), kFootprintTolerance));
    EXPECT_TRUE(exact_within_distance({0, 0}, {0.006, 0.008}, kFootprintTolerance) ==
                exact_detail::within_distance_by_cgal({0, 0}, {0.006, 0.008}, kFootprintTolerance));
}

TEST(ExactPredicates, FoldBackAndSegments) {
    EXPECT_TRUE(exact_folds_back({0, 0}, {2, 0}, {1, 0}));
    EXPECT_FALSE(exact_folds_back({0, 0}, {1, 0}, {2, 0}));
    EXPECT_FALSE(exact_folds_back({0, 0}, {1, 0}, {1, 1}));
    EXPECT_TRUE(exact_segments_touch({0, 0}, {2, 0}, {1, 0}, {1, 1}));   // T
    EXPECT_TRUE(exact_segments_touch({0, 0}, {2, 0}, {1, 0}, {3, 0}));   // overlapping
    EXPECT_FALSE(exact_segments_touch({0, 0}, {1, 0}, {2, 0}, {3, 0}));  // collinear, apart
    EXPECT_TRUE(exact_segments_touch({0, 0}, {2, 2}, {0, 2}, {2, 0}));   // crossing
}
