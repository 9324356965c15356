// barrier=retaining_wall ways into the scene's walls (osmparse/map/build_retaining_walls.h):
// their line in the way's direction, the tagged height or the default, the material, and what
// is dropped counted.
#include <gtest/gtest.h>

#include "osmparse/map/build_retaining_walls.h"

using namespace citygen;

namespace {

OsmWay wall_way(int64_t id, std::vector<LatLon> locations, std::vector<std::pair<std::string, std::string>> tags = {}) {
    OsmWay w;
    w.id = id;
    w.locations = std::move(locations);
    for (size_t k = 0; k < w.locations.size(); ++k) w.nodes.push_back(100 * id + static_cast<int64_t>(k));
    w.tags.entries = std::move(tags);
    return w;
}

}  // namespace

TEST(BuildRetainingWalls, TheLineTheHeightAndTheMaterial) {
    const Projection projection(43.7, 7.4);
    OsmData osm;
    osm.retaining_walls = {wall_way(1, {{43.7, 7.4}, {43.7, 7.401}}, {{"height", "3.5 m"}, {"material", "stone"}}),
                           wall_way(2, {{43.7, 7.4}, {43.7001, 7.4}, {43.7001, 7.4001}, {43.7, 7.4}}),
                           wall_way(3, {{43.7, 7.4}, {43.7, 7.4002}}, {{"height", "tall"}})};
    ParseReport report;
    const std::vector<RetainingWall> walls = build_retaining_walls(osm, projection, report);
    ASSERT_EQ(walls.size(), 3u);
    EXPECT_EQ(walls[0].osm, (OsmRef{OsmType::Way, 1}));
    ASSERT_EQ(walls[0].line.size(), 2u);
    EXPECT_NEAR(walls[0].line[0].x, 0, 1e-6);
    EXPECT_NEAR(walls[0].line[1].x, 80.5, 0.5) << "eastwards, in the way's direction";
    EXPECT_DOUBLE_EQ(walls[0].height, 3.5);
    EXPECT_TRUE(walls[0].height_tagged);
    EXPECT_EQ(walls[0].material, WallMaterial::Stone);
    EXPECT_EQ(walls[1].line.size(), 4u) << "a closed way repeats its first point";
    EXPECT_EQ(walls[1].line.front(), walls[1].line.back());
    EXPECT_DOUBLE_EQ(walls[1].height, kDefaultRetainingWallHeight);
    EXPECT_FALSE(walls[1].height_tagged);
    EXPECT_EQ(walls[1].material, WallMaterial::Concrete);
    EXPECT_DOUBLE_EQ(walls[2].height, kDefaultRetainingWallHeight);
    EXPECT_EQ(report.read_count(ReportKind::RetainingWalls), 3);
    EXPECT_EQ(report.kept_count(ReportKind::RetainingWalls), 3);
    EXPECT_EQ(report.note_count(ReportKind::RetainingWalls, ReportReason::RetainingWallHeightDefault), 1);
    EXPECT_EQ(report.note_count(ReportKind::RetainingWalls, ReportReason::RetainingWallHeightUnusable), 1);
}

TEST(BuildRetainingWalls, WhatCannotBeAWallIsCounted) {
    const Projection projection(43.7, 7.4);
    OsmData osm;
    OsmWay clipped = wall_way(4, {{43.7, 7.4}, {43.7, 7.401}});
    clipped.cut_after = true;
    OsmWay rest = wall_way(4, {{43.71, 7.4}, {43.71, 7.401}});  // the same way's second run
    osm.retaining_walls = {wall_way(1, {}), wall_way(2, {{43.7, 7.4}, {43.7, 7.4}}), clipped, rest};
    ParseReport report;
    const std::vector<RetainingWall> walls = build_retaining_walls(osm, projection, report);
    EXPECT_EQ(walls.size(), 2u);
    EXPECT_EQ(report.read_count(ReportKind::RetainingWalls), 3) << "ways, not runs";
    EXPECT_EQ(report.dropped_count(ReportKind::RetainingWalls, ReportReason::NodesMissing), 1);
    EXPECT_EQ(report.dropped_count(ReportKind::RetainingWalls, ReportReason::ZeroLength), 1);
    EXPECT_EQ(report.note_count(ReportKind::RetainingWalls, ReportReason::ClippedAtEdge), 1);
}
