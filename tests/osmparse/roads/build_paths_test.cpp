// Paths and rails: classes and widths from tags, strips laid out with the road rules (a
// footway crossing a street, steps, a railway; a tunnel left out), mapped sidewalks
// replacing generated ones, and valid strips on real extracts.
#include <gtest/gtest.h>

#include <filesystem>

#include "common/projection.h"
#include "osmparse/pipeline.h"
#include "osmparse/polygons/ring_is_simple.h"
#include "osmparse/read/read_osm.h"
#include "osmparse/roads/build_paths.h"
#include "tests/osmparse/parse_quietly.h"

using namespace citygen;
using citygen::test::parse_quietly;

namespace {

OsmTags tags(std::vector<std::pair<std::string, std::string>> entries) {
    OsmTags t;
    t.entries = std::move(entries);
    return t;
}

void expect_valid_strips(const Scene& s) {
    for (const PathEdge& p : s.paths) {
        ASSERT_EQ(p.quad.size(), 4u);
        EXPECT_GT(signed_area(p.quad), 0) << to_string(p.osm);
        EXPECT_TRUE(ring_is_simple(p.quad)) << to_string(p.osm);
        if (p.from_joint >= 0) EXPECT_LT(p.from_joint, static_cast<int>(s.path_joints.size()));
    }
    for (const Joint& j : s.path_joints) {
        EXPECT_GT(signed_area(j.polygon), 0) << to_string(j.osm);
        for (uint32_t e : j.edges) EXPECT_LT(e, s.paths.size());
    }
}

}  // namespace

TEST(PathTags, ClassesAndWidths) {
    EXPECT_EQ(path_class_of(tags({{"highway", "footway"}})), PathClass::Footway);
    EXPECT_EQ(path_class_of(tags({{"highway", "steps"}})), PathClass::Steps);
    EXPECT_EQ(path_class_of(tags({{"highway", "pedestrian"}})), PathClass::Pedestrian);
    EXPECT_EQ(path_class_of(tags({{"railway", "tram"}})), PathClass::Tram);
    EXPECT_EQ(path_class_of(tags({{"railway", "abandoned"}})), std::nullopt);
    EXPECT_EQ(path_class_of(tags({{"highway", "residential"}})), std::nullopt);
    EXPECT_DOUBLE_EQ(path_width(tags({}), PathClass::Footway, nullptr), 2.0);
    EXPECT_DOUBLE_EQ(path_width(tags({{"width", "3.5"}}), PathClass::Footway, nullptr), 3.5);
    ParseReport report;
    EXPECT_DOUBLE_EQ(path_width(tags({{"width", "banana"}}), PathClass::Track, &report), 3.0);
    EXPECT_EQ(report.note_count(ReportKind::PathEdges, ReportReason::WidthTagUnusable), 1);
}

TEST(PathTags, EveryClassHasItsReportRow) {
    for (int i = 0; i < kPathClassCount; ++i) {
        const PathClass c = static_cast<PathClass>(i);
        EXPECT_EQ(std::string(text_of(path_class_row(c))), std::string("path: ") + to_string(c));
    }
}

TEST(Paths, FootwayCrossingAStreetStepsAndARailwayButNoTunnel) {
    ParseReport report;
    const Scene s = parse_quietly(std::string(CITYGEN_SOURCE_DIR) + "/tests/data/map_paths.osm", report);
    size_t footways = 0, steps = 0, rails = 0;
    for (const PathEdge& p : s.paths) {
        footways += p.path_class == PathClass::Footway;
        steps += p.path_class == PathClass::Steps;
        rails += p.path_class == PathClass::Rail;
        if (p.path_class == PathClass::Steps) EXPECT_DOUBLE_EQ(p.width, 3.0);
        EXPECT_NE(p.osm.id, 14) << "the railway in the tunnel";
    }
    EXPECT_EQ(footways, 2u);  // the crossing footway and the mapped sidewalk
    EXPECT_EQ(steps, 1u);
    EXPECT_EQ(rails, 1u);
    EXPECT_EQ(report.dropped_count(ReportKind::PathWays, ReportReason::Tunnel), 1);
    expect_valid_strips(s);
    // The mapped sidewalk on the north side replaces ours there; the south one stays.
    EXPECT_EQ(report.dropped_count(ReportKind::SidewalkStrips, ReportReason::ReplacedByMappedSidewalk), 1);
    EXPECT_EQ(s.sidewalks.size(), 1u);
}

TEST(Paths, MonacoGivesValidStripsAndJoints) {
    for (const char* name : {"monaco.osm.pbf"}) {
        const std::string path = std::string(CITYGEN_SHARED_DATA_DIR) + "/" + name;
        if (!std::filesystem::exists(path)) continue;
        ParseReport report;
        const Scene s = parse_quietly(path, report);
        EXPECT_GT(s.paths.size(), 1000u) << name;
        expect_valid_strips(s);
    }
}

// The pipeline keeps only the path ways (with the tags build_paths reads) from the road
// stages to the paths: the paths and their report must be what all the highways give.
TEST(Paths, KeepPathWaysKeepsWhatBuildPathsReads) {
    ParseReport read_report;
    OsmData osm = read_osm(std::string(CITYGEN_SOURCE_DIR) + "/tests/data/map_paths.osm", true, read_report);
    for (OsmWay& w : osm.highways) w.tags.entries.push_back({"surface", "asphalt"});  // read by no path rule
    const Projection projection(0.5 * (osm.min.lat + osm.max.lat), 0.5 * (osm.min.lon + osm.max.lon));
    const RoadParams params;
    ParseReport all_report, kept_report;
    const PathSurface all = build_paths(osm, projection, params, false, all_report);
    const size_t ways = osm.highways.size();
    keep_path_ways(osm.highways);
    EXPECT_LT(osm.highways.size(), ways);  // the street is gone
    for (const OsmWay& w : osm.highways) {
        EXPECT_TRUE(path_class_of(w.tags).has_value());
        EXPECT_EQ(w.tags.get("surface"), nullptr);
    }
    const PathSurface kept = build_paths(osm, projection, params, false, kept_report);
    ASSERT_GT(all.paths.size(), 0u);
    ASSERT_EQ(kept.paths.size(), all.paths.size());
    for (size_t i = 0; i < all.paths.size(); ++i) {
        EXPECT_EQ(kept.paths[i].osm, all.paths[i].osm);
        EXPECT_EQ(kept.paths[i].quad, all.paths[i].quad);
        EXPECT_EQ(kept.paths[i].width, all.paths[i].width);
        EXPECT_EQ(kept.paths[i].path_class, all.paths[i].path_class);
        EXPECT_EQ(kept.paths[i].sidewalk, all.paths[i].sidewalk);
    }
    ASSERT_EQ(kept.joints.size(), all.joints.size());
    for (size_t i = 0; i < all.joints.size(); ++i) EXPECT_EQ(kept.joints[i].polygon, all.joints[i].polygon);
    for (ReportKind row : {ReportKind::PathWays, ReportKind::PathEdges, ReportKind::PathJoints}) {
        EXPECT_EQ(kept_report.read_count(row), all_report.read_count(row)) << text_of(row);
        EXPECT_EQ(kept_report.kept_count(row), all_report.kept_count(row)) << text_of(row);
    }
    EXPECT_EQ(kept_report.dropped_count(ReportKind::PathWays, ReportReason::Tunnel),
              all_report.dropped_count(ReportKind::PathWays, ReportReason::Tunnel));
    EXPECT_EQ(kept_report.dropped_count(ReportKind::PathWays, ReportReason::Tunnel), 1);
}
