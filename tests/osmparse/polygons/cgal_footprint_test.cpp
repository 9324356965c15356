// CGAL's part of footprint cleaning (osmparse/polygons/cgal_footprint.h) and the cases where the
// hand-written float code went wrong: a merged outline crossing a hole, a merged hole crossing
// a hole 6 mm away, pieces of a split ring simplified apart. Validity is asserted with CGAL's
// own check (is_valid_polygon_with_holes), not with the code under test.
#include <gtest/gtest.h>

#include <cmath>

#include "osmparse/polygons/cgal_footprint.h"
#include "osmparse/polygons/clean_footprint.h"
#include "osmparse/polygons/polygon_overlap.h"

using namespace citygen;

namespace {

std::vector<Footprint> clean(const Ring& outer, const std::vector<Ring>& holes, ParseReport& report) {
    return clean_footprint(outer, holes, BuildingParams{}, report, ReportKind::Buildings);
}

Ring rectangle(double x0, double y0, double x1, double y1) { return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}}; }

double area_of(const std::vector<Footprint>& polygons) {
    double area = 0;
    for (const Footprint& f : polygons) {
        area += signed_area(f.outer);
        for (const Ring& h : f.holes) area += signed_area(h);
    }
    return area;
}

void expect_valid(const std::vector<Footprint>& polygons) {
    for (const Footprint& f : polygons) EXPECT_TRUE(polygon_is_valid_exact(f.outer, f.holes));
}

}  // namespace

TEST(CgalFootprint, OrientationIsExact) {
    EXPECT_EQ(ring_orientation_exact(rectangle(0, 0, 1, 1)), 1);
    Ring cw = rectangle(0, 0, 1, 1);
    std::reverse(cw.begin(), cw.end());
    EXPECT_EQ(ring_orientation_exact(cw), -1);
    // A sliver 1e-9 m thick far from the origin: the shoelace sum in double loses it, the exact
    // orientation does not.
    const Ring sliver{{10000, 10000}, {10000.5, 10000.5}, {10001, 10001 + 1e-9}};
    EXPECT_EQ(ring_orientation_exact(sliver), 1);
}

TEST(CgalFootprint, SplitsABowTieIntoTwoTriangles) {
    const auto loops = split_at_crossings_exact({{0, 0}, {10, 10}, {10, 0}, {0, 10}});
    ASSERT_EQ(loops.size(), 2u);
    for (const Ring& loop : loops) EXPECT_NEAR(std::fabs(signed_area(loop)), 25, 1e-9);
}

TEST(CgalFootprint, SplitDropsASpikeFoldingBackOverAnEdge) {
    // Out along the bottom edge to (15, 0) and back: the doubled stretch is inside neither way.
    ParseReport report;
    const auto polygons = clean({{0, 0}, {15, 0}, {12, 0}, {12, 10}, {0, 10}}, {}, report);
    ASSERT_EQ(polygons.size(), 1u);
    EXPECT_NEAR(area_of(polygons), 120, 1e-6);
    expect_valid(polygons);
}

TEST(CgalFootprint, SplitKeepsTheEvenOddInside) {
    // A ring that winds twice around the middle: the middle is outside under even-odd, so it
    // becomes a hole of the outer loop.
    const Ring twice{{0, 0}, {30, 0}, {30, 30}, {0, 30}, {0, 10}, {20, 10}, {20, 20}, {10, 20}, {10, 5}, {0, 5}};
    ParseReport report;
    const auto polygons = clean(twice, {}, report);
    expect_valid(polygons);
    EXPECT_GT(area_of(polygons), 0);
    EXPECT_LT(area_of(polygons), 900);  // not all of the square: the doubly wound part is out
}

TEST(CgalFootprint, SimplifiedOutlineNeverCrossesAHole) {
    // The bottom edge bends out by 0.4 m (a 4.6 degree turn, merged by default); the hole reaches
    // below the merged edge's line. Merged on its own the outline crossed the hole, which was
    // then dropped as "outside or touching the outline".
    const Ring outer{{0, 0}, {10, -0.4}, {20, 0}, {20, 20}, {0, 20}};
    const Ring hole = rectangle(9, -0.3, 11, 2.2);
    ParseReport report;
    const auto polygons = clean(outer, {hole}, report);
    ASSERT_EQ(polygons.size(), 1u);
    ASSERT_EQ(polygons[0].holes.size(), 1u);
    expect_valid(polygons);
    EXPECT_EQ(report.dropped_count(ReportKind::BuildingHoles, ReportReason::HoleOutside), 0);
}

TEST(CgalFootprint, SimplifiedHoleNeverCrossesANearlyTouchingHole) {
    // Hole A's right side bends in by 8 cm (a 4.6 degree turn); hole B sits in that bend, 6 mm
    // from it. Merged on its own, A's side became straight through B.
    const Ring outer = rectangle(0, 0, 12, 8);
    const Ring a{{2, 2}, {6, 2}, {5.92, 4}, {6, 6}, {2, 6}};
    const Ring b = rectangle(5.95, 3.4, 9.35, 4.6);
    ParseReport report;
    const auto polygons = clean(outer, {a, b}, report);
    ASSERT_EQ(polygons.size(), 1u);
    EXPECT_EQ(polygons[0].holes.size(), 2u);
    expect_valid(polygons);
    EXPECT_EQ(report.dropped_count(ReportKind::BuildingHoles, ReportReason::HoleOverlaps), 0);
}

TEST(CgalFootprint, HolesThatReallyOverlapAreStillDropped) {
    ParseReport report;
    const auto polygons = clean(rectangle(0, 0, 20, 20), {rectangle(2, 2, 8, 8), rectangle(6, 6, 12, 12)}, report);
    ASSERT_EQ(polygons.size(), 1u);
    EXPECT_EQ(polygons[0].holes.size(), 1u);
    EXPECT_EQ(report.dropped_count(ReportKind::BuildingHoles, ReportReason::HoleOverlaps), 1);
    expect_valid(polygons);
}

TEST(CgalFootprint, SimplifyKeepingTopologyMergesSmallTurnsOnly) {
    // A 2-degree kink is merged, a real corner is not; vertices are only removed.
    const double kink = 5 * std::tan(2 * kPi / 180);
    const Ring ring{{0, 0}, {5, -kink}, {10, 0}, {10, 10}, {0, 10}};
    const auto out = simplify_keeping_topology({ring}, 5);
    ASSERT_EQ(out.size(), 1u);
    EXPECT_EQ(out[0].size(), 4u);
    for (Vec2 p : out[0]) EXPECT_NE(std::find(ring.begin(), ring.end(), p), ring.end());
    EXPECT_EQ(simplify_keeping_topology({ring}, 1)[0].size(), 5u);
}

TEST(CgalFootprint, RealSelfIntersectingOutlineFromKaiserslautern) {
    // Way 102538460 (metres from its first node): a small twist near (-42, -4). Its two pieces
    // are simplified together now; the twist's triangle is below min area and goes.
    const Ring ring{{0, 0},         {-22.44, -21.00}, {-39.81, -12.16}, {-36.91, -6.63},
                    {-41.98, -3.32}, {-42.70, -5.53},  {-32.57, 12.16},  {-30.40, 16.58}};
    ParseReport report;
    const auto polygons = clean(ring, {}, report);
    ASSERT_EQ(polygons.size(), 1u);
    expect_valid(polygons);
    // The big loop of the split survives, less only what merging near-collinear edges shaves.
    double largest = 0;
    for (const Ring& piece : split_self_intersections(ring)) largest = std::max(largest, std::fabs(signed_area(piece)));
    EXPECT_GT(largest, 500);
    EXPECT_NEAR(area_of(polygons), largest, 0.01 * largest);
}

TEST(CgalFootprint, ExactOverlapAgreesWithTheHandWrittenOne) {
    Building b;
    b.outer = rectangle(0, 0, 10, 10);
    b.holes = {{{4, 4}, {4, 6}, {6, 6}, {6, 4}}};
    const Ring l_shape{{-5, -5}, {5, -5}, {5, 5}, {0, 5}, {0, 0}, {-5, 0}};  // concave
    EXPECT_NEAR(overlap_area(l_shape, b), overlap_area_exact(l_shape, b.outer, b.holes), 1e-9);
    EXPECT_NEAR(overlap_area_exact(l_shape, b.outer, b.holes), 25 - 1, 1e-9);
    EXPECT_NEAR(overlap_area_exact(rectangle(20, 20, 30, 30), b.outer, b.holes), 0, 0);
}

// Rings that cross slightly (pieces rounded to float) made the triangulation insert their
// crossing points, so the "simplified" rings held points that were in no input ring.
TEST(CgalFootprint, SimplifyKeepingTopologyAddsNoPointsWhereRingsCross) {
    const Ring square{{0, 0}, {5, 0.01}, {10, 0}, {10, 10}, {0, 10}};
    const Ring crossing{{9.999, 4}, {12, 4}, {12, 6}, {9.999, 6}};  // 1 mm over the square's right side
    const std::vector<Ring> out = simplify_keeping_topology({square, crossing}, 5);
    ASSERT_EQ(out.size(), 2u);
    EXPECT_EQ(out[0], square);
    EXPECT_EQ(out[1], crossing);
}
