// Paths and rails: classes and widths from tags, strips laid out with the road rules (a
// footway crossing a street, steps, a railway; a tunnel left out), mapped sidewalks
// replacing generated ones, and valid strips on real extracts.
#include <gtest/gtest.h>

#include <filesystem>

#include "build_paths.h"
#include "parse_quietly.h"
#include "pipeline.h"
#include "ring_is_simple.h"

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
    EXPECT_EQ(report.note_count("path edges", "width tag unusable, fell back"), 1);
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
    EXPECT_EQ(report.dropped_count("path ways", "tunnel"), 1);
    expect_valid_strips(s);
    // The mapped sidewalk on the north side replaces ours there; the south one stays.
    EXPECT_EQ(report.dropped_count("sidewalk strips", "replaced by a mapped sidewalk (footway=sidewalk)"), 1);
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
