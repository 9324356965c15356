// Bridges mapped only by layer (osmparse/terrain/bridges_from_layers.h): a way above a lower way
// or water is a bridge; one that only meets a lower way at its end, or crosses nothing, is not.
#include <gtest/gtest.h>

#include "osmparse/terrain/bridges_from_layers.h"

using namespace citygen;

namespace {

RoadEdge road(int64_t way, Vec2 a, Vec2 b) {
    RoadEdge r;
    r.osm = {OsmType::Way, way};
    r.centreline = {a, b};
    return r;
}

PathEdge path(int64_t way, Vec2 a, Vec2 b) {
    PathEdge p;
    p.osm = {OsmType::Way, way};
    p.centreline = {a, b};
    return p;
}

}  // namespace

TEST(WayLayers, WholeLayersFromMinusFiveToFiveButZero) {
    OsmData osm;
    const std::pair<int64_t, const char*> tagged[] = {{1, "1"}, {2, "-1"}, {3, "0"}, {4, "1;2"}, {5, "x"}, {6, "7"}, {7, "2.5"}};
    for (const auto& [id, value] : tagged) {
        OsmWay w;
        w.id = id;
        w.tags.entries = {{"highway", "residential"}, {"layer", value}};
        osm.highways.push_back(w);
    }
    OsmWay rail;
    rail.id = 8;
    rail.tags.entries = {{"railway", "rail"}, {"layer", "2"}};
    osm.railways.push_back(rail);
    const std::unordered_map<int64_t, int> layers = way_layers(osm);
    EXPECT_EQ(layers, (std::unordered_map<int64_t, int>{{1, 1}, {2, -1}, {8, 2}}));
}

TEST(MarkLayeredBridges, AWayAboveALowerWayOrWaterIsABridgeAndNoOtherIs) {
    std::vector<RoadEdge> roads = {
        road(1, {-50, 0}, {50, 0}),     // layer 0, east-west
        road(2, {0, -50}, {0, 50}),     // layer 1 across road 1: a bridge
        road(3, {50, 0}, {50, 60}),     // layer 1, meets road 1 at its end only
        road(4, {200, 0}, {300, 0}),    // layer 1 over nothing
        road(5, {-40, 5}, {-40, 40}),   // layer 1 across road 6 only, which is higher
        road(6, {-60, 10}, {-20, 10}),  // layer 2
    };
    std::vector<PathEdge> paths = {path(7, {500, -20}, {500, 20}),  // layer 1 over the pond
                                   path(8, {600, -20}, {600, 20})};  // layer 1 beside it
    LandCover pond;
    pond.cover = LandCoverClass::Water;
    pond.outer = {{480, -10}, {520, -10}, {520, 10}, {480, 10}};
    const std::unordered_map<int64_t, int> layers = {{2, 1}, {3, 1}, {4, 1}, {5, 1}, {6, 2}, {7, 1}, {8, 1}};
    ParseReport report;
    mark_layered_bridges(roads, paths, layers, {pond}, report);
    std::vector<bool> road_bridges, path_bridges;
    for (const RoadEdge& r : roads) road_bridges.push_back(r.bridge);
    for (const PathEdge& p : paths) path_bridges.push_back(p.bridge);
    EXPECT_EQ(road_bridges, (std::vector<bool>{false, true, false, false, false, true}));
    EXPECT_EQ(path_bridges, (std::vector<bool>{true, false}));
    EXPECT_EQ(report.note_count(ReportKind::RoadEdges, ReportReason::BridgeFromLayer), 2);
    EXPECT_EQ(report.note_count(ReportKind::PathEdges, ReportReason::BridgeFromLayer), 1);
}

TEST(MarkLayeredBridges, AFootbridgeWhollyInsideWaterIsABridge) {
    std::vector<RoadEdge> roads;
    std::vector<PathEdge> paths = {path(1, {-5, 0}, {5, 0})};
    LandCover lake;
    lake.cover = LandCoverClass::Water;
    lake.outer = {{-100, -100}, {100, -100}, {100, 100}, {-100, 100}};
    ParseReport report;
    mark_layered_bridges(roads, paths, {{1, 1}}, {lake}, report);
    EXPECT_TRUE(paths[0].bridge);
}
