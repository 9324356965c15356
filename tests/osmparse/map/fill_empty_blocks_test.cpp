// --fill-empty-blocks on a residential grid of two blocks: the left one mapped, the right one
// empty (tests/data/empty_block.osm).
#include <gtest/gtest.h>

#include <set>

#include "common/scene_io.h"
#include "osmparse/pipeline.h"
#include "osmparse/polygons/polygon_overlap.h"
#include "tests/osmparse/parse_quietly.h"
#include "tests/test_support.h"

using namespace citygen;
using citygen::test::parse_quietly;
using citygen::test::source_path;

namespace {

Scene parse(bool fill, ParseReport& report) {
    ParseParams params;
    params.blocks.enabled = fill;
    return parse_quietly(source_path("tests/data/empty_block.osm"), report, params);
}

double overlap(const Ring& a, const Ring& b) {
    Ring ccw = b;
    if (signed_area(ccw) < 0) std::reverse(ccw.begin(), ccw.end());
    double area = 0;
    for (const Ring& t : triangulate(ccw)) area += clipped_area(a, t);
    return area;
}

}  // namespace

TEST(FillEmptyBlocks, OnlyWhenAskedAndOnlyInTheEmptyBlock) {
    ParseReport plain_report, report;
    const Scene plain = parse(false, plain_report);
    for (const Building& b : plain.buildings) EXPECT_FALSE(b.generated);
    const Scene filled = parse(true, report);

    // The scene's origin is the centre of the grid: the middle road runs along x = 0, between the
    // mapped block (x < 0) and the empty one.
    const double middle_x = 0;
    std::set<int64_t> ids;
    int generated = 0;
    for (const Building& b : filled.buildings) {
        if (!b.generated) continue;
        ++generated;
        EXPECT_TRUE(ids.insert(b.osm.id).second) << "identities are unique";
        EXPECT_LT(b.osm.id, 0) << "no OSM identity";
        EXPECT_GT(bounds_of(b.outer).min.x, middle_x + 3 + 2) << "in the empty block, off the road and sidewalk";
        EXPECT_GT(b.height, 2.0);
        EXPECT_EQ(b.height_rule, HeightRule::TypeAndArea);
        for (const RoadEdge& r : filled.roads) EXPECT_LT(overlap(b.outer, r.quad), 1e-6) << to_string(b.osm);
        for (const Joint& j : filled.joints) EXPECT_LT(overlap(b.outer, j.polygon), 1e-6) << to_string(b.osm);
        for (const Sidewalk& s : filled.sidewalks) EXPECT_LT(overlap(b.outer, s.polygon), 1e-6) << to_string(b.osm);
        for (const Building& m : filled.buildings) {
            if (&m == &b) continue;
            EXPECT_LT(overlap(b.outer, m.outer), 1e-6) << to_string(b.osm) << " vs " << to_string(m.osm);
        }
    }
    EXPECT_GE(generated, 6);
    EXPECT_EQ(filled.buildings.size(), plain.buildings.size() + generated);
    EXPECT_EQ(report.kept_count(ReportKind::GeneratedBuildings), generated);
    EXPECT_EQ(report.note_count(ReportKind::GeneratedBuildings, ReportReason::BlockFilled), 1);
    EXPECT_GT(report.dropped_count(ReportKind::GeneratedBuildings, ReportReason::LotWithoutAccess), 0);
    // The header says it was asked for; the same input gives the same bytes.
    bool in_header = false;
    for (const auto& [k, v] : filled.header.options) in_header |= k == "fill-empty-blocks";
    EXPECT_TRUE(in_header);
    ParseReport again;
    EXPECT_EQ(encode_scene(parse(true, again)), encode_scene(filled));
}
