// The painted road pattern render evaluates from a scene's lanes and crossings, on the lanes
// fixture's golden scene: zebra stripes, the dashed centre line, edge lines, a stop line across
// the right half, cycle-lane lines.
#include <gtest/gtest.h>

#include <vector>

#include "common/scene_io.h"
#include "render/geometry/road_markings.h"
#include "render/materials/materials.h"
#include "tests/test_scenes.h"

using namespace citygen;
using citygen::test::road_of_way;

TEST(Markings, PaintedPatternOfTheLanesFixture) {
    const Scene s = load_scene(std::string(CITYGEN_SOURCE_DIR) + "/tests/golden/map_lanes.scene");
    const RoadEdge* primary = road_of_way(s, 10);
    ASSERT_NE(primary, nullptr);
    const Crossing* zebra = nullptr;
    const Crossing* stop = nullptr;
    for (const Crossing& c : s.crossings) (c.kind == CrossingKind::Zebra ? zebra : stop) = &c;
    ASSERT_TRUE(zebra && stop);

    // The painted pattern: zebra stripes alternate across the road at the crossing.
    const RoadEdge& street = s.roads[zebra->road];
    const Vec2 d = normalize(street.centreline.back() - street.centreline.front()), n = perp_left(d);
    const std::vector<const Crossing*> on_street{zebra};
    const RoadPaint street_paint = road_paint(street);
    int paint = 0, bare = 0;
    for (double x = -2.6; x <= 2.6; x += 0.1) {
        const uint16_t m = road_surface_material(street_paint, on_street, zebra->position + n * x);
        paint += m == kPaintWhite;
        bare += m == kAsphalt || m == kAsphaltLight;
    }
    EXPECT_GT(paint, 15);
    EXPECT_GT(bare, 15);
    // Away from the crossing: the dashed centre line, asphalt beside it.
    const Vec2 mid = zebra->position + d * 20;
    bool centre_painted = false;
    for (double t = 0; t < 9; t += 0.5)
        centre_painted |= road_surface_material(street_paint, on_street, mid + d * t) == kPaintWhite;
    EXPECT_TRUE(centre_painted);
    EXPECT_NE(road_surface_material(street_paint, on_street, mid + n * 1.5), kPaintWhite);
    // The primary's edge line, 0.3 m inside its edge; its stop line across the right half only.
    const std::vector<const Crossing*> on_primary{stop};
    const RoadPaint primary_paint = road_paint(*primary);
    const Vec2 pd = normalize(primary->centreline.back() - primary->centreline.front()), pn = perp_left(pd);
    const Vec2 far = primary->centreline.front() + pd * 30;
    EXPECT_EQ(road_surface_material(primary_paint, on_primary, far + pn * (0.5 * primary->width - 0.3)), kPaintWhite);
    EXPECT_EQ(road_surface_material(primary_paint, on_primary, stop->position - pn * 4.1), kPaintWhite);
    EXPECT_NE(road_surface_material(primary_paint, on_primary, stop->position + pn * 4.1), kPaintWhite);
    // The cycle lanes' lines 1.5 m inside each edge, bare asphalt in the cycle lane.
    EXPECT_EQ(road_surface_material(primary_paint, on_primary, far + pn * (0.5 * primary->width - 1.5)), kPaintWhite);
    EXPECT_EQ(road_surface_material(primary_paint, on_primary, far - pn * (0.5 * primary->width - 1.5)), kPaintWhite);
    EXPECT_NE(road_surface_material(primary_paint, on_primary, far - pn * (0.5 * primary->width - 0.9)), kPaintWhite);
}
