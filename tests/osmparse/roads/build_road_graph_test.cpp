// The road graph: ways split at shared nodes, nearly collinear runs merged, non-roads
// left out and counted.
#include <gtest/gtest.h>

#include "osmparse/roads/build_road_graph.h"

using namespace citygen;

namespace {

const Projection kProjection(52.5, 13.4);

OsmWay way(int64_t id, std::vector<std::pair<int64_t, Vec2>> nodes, OsmTags tags) {
    OsmWay w;
    w.id = id;
    w.tags = std::move(tags);
    for (auto [node, at] : nodes) {
        LatLon l;
        kProjection.to_wgs84(at, l.lat, l.lon);
        w.nodes.push_back(node);
        w.locations.push_back(l);
    }
    return w;
}

OsmTags highway(const char* v) { return OsmTags{{{"highway", v}}}; }

}  // namespace

TEST(BuildRoadGraph, SplitsAtSharedNodesAndMergesCollinearRuns) {
    OsmData osm;
    // Way 1: straight west-east with a collinear node 2 and a junction at node 3.
    osm.highways.push_back(way(1, {{1, {-100, 0}}, {2, {-50, 0.1}}, {3, {0, 0}}, {4, {60, 0}}}, highway("residential")));
    // Way 2 starts at node 3 and bends by 30 degrees at node 6: no merge there.
    osm.highways.push_back(way(2, {{3, {0, 0}}, {5, {0, 40}}, {6, {20, 74.6}}}, highway("service")));
    ParseReport report;
    const RoadGraph g = build_road_graph(osm, kProjection, RoadParams{}, report);
    ASSERT_EQ(g.edges.size(), 4u);
    EXPECT_EQ(g.edges[0].from_node, 1);  // 1-2-3 merged: node 2 is straight on
    EXPECT_EQ(g.edges[0].to_node, 3);
    EXPECT_EQ(g.edges[1].from_node, 3);
    EXPECT_EQ(g.edges[1].to_node, 4);
    EXPECT_EQ(g.edges[2].to_node, 5);   // 30 degree turn: two edges
    EXPECT_EQ(g.edges[3].from_node, 5);
    EXPECT_EQ(g.edges[0].road_class, RoadClass::Residential);
    EXPECT_EQ(g.edges[2].road_class, RoadClass::Service);
    EXPECT_DOUBLE_EQ(g.edges[2].width, default_road_width("service", false));
    EXPECT_TRUE(g.edges[0].sidewalk_left && g.edges[0].sidewalk_right);
    EXPECT_FALSE(g.edges[2].sidewalk_left || g.edges[2].sidewalk_right);
    EXPECT_EQ(report.note_count(ReportKind::RoadEdges, ReportReason::MergedCollinear), 1);
}

TEST(BuildRoadGraph, MergeAngleIsAnOption) {
    OsmData osm;
    osm.highways.push_back(way(1, {{1, {0, 0}}, {2, {50, 0}}, {3, {100, 6}}}, highway("residential")));  // ~7 deg
    ParseReport report;
    RoadParams params;
    params.merge_angle_deg = 10;
    EXPECT_EQ(build_road_graph(osm, kProjection, params, report).edges.size(), 2u)
        << "node 2 lies 3 m off the merged piece: kept";
    osm.highways[0] = way(1, {{1, {0, 0}}, {2, {50, 0.5}}, {3, {100, 0.6}}}, highway("residential"));
    EXPECT_EQ(build_road_graph(osm, kProjection, params, report).edges.size(), 1u);
    params.merge_angle_deg = 0.1;
    EXPECT_EQ(build_road_graph(osm, kProjection, params, report).edges.size(), 2u);
}

TEST(BuildRoadGraph, LeavesOutNonCarriagewaysTunnelsAndDuplicates) {
    OsmData osm;
    osm.highways.push_back(way(1, {{1, {0, 0}}, {2, {50, 0}}}, highway("footway")));
    osm.highways.push_back(way(2, {{3, {0, 10}}, {4, {50, 10}}}, OsmTags{{{"highway", "primary"}, {"tunnel", "yes"}}}));
    osm.highways.push_back(way(3, {{5, {0, 20}}, {6, {50, 20}}}, OsmTags{{{"highway", "primary"}, {"bridge", "yes"}}}));
    osm.highways.push_back(way(4, {{6, {50, 20}}, {5, {0, 20}}}, highway("primary")));  // same piece again
    osm.highways.push_back(way(5, {{7, {0, 30}}, {8, {50, 30}}}, OsmTags{{{"highway", "service"}, {"area", "yes"}}}));
    ParseReport report;
    const RoadGraph g = build_road_graph(osm, kProjection, RoadParams{}, report);
    ASSERT_EQ(g.edges.size(), 1u);
    EXPECT_EQ(g.edges[0].way_id, 3);
    EXPECT_TRUE(g.edges[0].bridge);
    EXPECT_EQ(report.dropped_count(ReportKind::RoadWays, ReportReason::Tunnel), 1);
    EXPECT_EQ(report.dropped_count(ReportKind::RoadWays, ReportReason::AreaYes), 1);
    EXPECT_EQ(report.dropped_count(ReportKind::RoadEdges, ReportReason::DuplicatePiece), 1);
}

// covered=* (not no) roads stay in the graph; with a height field each kept one is noted.
TEST(BuildRoadGraph, NotesCoveredWaysOnlyWithTerrain) {
    OsmData osm;
    osm.highways.push_back(way(1, {{1, {0, 0}}, {2, {50, 0}}}, OsmTags{{{"highway", "residential"}, {"covered", "yes"}}}));
    osm.highways.push_back(way(2, {{3, {0, 10}}, {4, {50, 10}}}, OsmTags{{{"highway", "service"}, {"covered", "arcade"}}}));
    osm.highways.push_back(way(3, {{5, {0, 20}}, {6, {50, 20}}}, OsmTags{{{"highway", "service"}, {"covered", "no"}}}));
    osm.highways.push_back(way(4, {{7, {0, 30}}, {8, {50, 30}}},
                               OsmTags{{{"highway", "primary"}, {"covered", "yes"}, {"tunnel", "yes"}}}));
    ParseReport flat, hilly;
    EXPECT_EQ(build_road_graph(osm, kProjection, RoadParams{}, flat).edges.size(), 3u);
    EXPECT_EQ(build_road_graph(osm, kProjection, RoadParams{}, hilly, true).edges.size(), 3u);
    EXPECT_EQ(flat.note_count(ReportKind::RoadWays, ReportReason::Covered), 0);
    EXPECT_EQ(hilly.note_count(ReportKind::RoadWays, ReportReason::Covered), 2) << "the tunnel is dropped";
}
