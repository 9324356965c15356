// Tile scenes merged into one: indices between lists moved with them, edge ends a tile cut from
// their joint linked again, and scenes that do not share a frame, seed or terrain refused.
#include <gtest/gtest.h>

#include "common/error.h"
#include "render/scene/merge_scenes.h"

using namespace citygen;

namespace {

RoadEdge road(int64_t from, int64_t to, int from_joint, int to_joint) {
    RoadEdge r;
    r.osm = {OsmType::Way, 100 + from};
    r.from_node = from, r.to_node = to;
    r.from_joint = from_joint, r.to_joint = to_joint;
    return r;
}

// A tile with one road joint at `node`, road 0 ending at it, road 1 without joints; a sidewalk
// and crossing on road 1; a path and a path joint.
Scene tile(int64_t node, Vec2 min, Vec2 max) {
    Scene s;
    s.header.origin_lat = 49.4, s.header.origin_lon = 7.8, s.header.projection = "transverse-mercator";
    s.header.seed = 1;
    s.header.bounds_min = min, s.header.bounds_max = max;
    s.ground.min = min, s.ground.max = max;
    s.roads = {road(node - 1, node, -1, 0), road(node + 10, node + 11, -1, -1)};
    Joint j;
    j.osm = {OsmType::Node, node};
    j.edges = {0};
    s.joints = {j};
    Sidewalk w;
    w.road = 1, w.joint = 0;
    s.sidewalks = {w};
    Crossing c;
    c.road = 1;
    s.crossings = {c};
    PathEdge p;
    p.from_node = node, p.to_node = node + 1, p.to_joint = 0;
    s.paths = {p};
    Joint pj;
    pj.osm = {OsmType::Node, node + 1};
    pj.edges = {0};
    s.path_joints = {pj};
    return s;
}

TEST(MergeScenes, MovesIndicesWithTheirLists) {
    const Scene m = merge_scenes({tile(1, {0, 0}, {10, 10}), tile(50, {10, -5}, {20, 10})}, {"a", "b"});
    ASSERT_EQ(m.roads.size(), 4u);
    EXPECT_EQ(m.roads[2].to_joint, 1);
    EXPECT_EQ(m.joints[1].edges, std::vector<uint32_t>{2});
    EXPECT_EQ(m.sidewalks[1].road, 3);
    EXPECT_EQ(m.sidewalks[1].joint, 1);
    EXPECT_EQ(m.crossings[1].road, 3);
    EXPECT_EQ(m.paths[1].to_joint, 1);
    EXPECT_EQ(m.path_joints[1].edges, std::vector<uint32_t>{1});
    EXPECT_EQ(m.header.bounds_min.y, -5);
    EXPECT_EQ(m.header.bounds_max.x, 20);
    EXPECT_EQ(m.ground.min.y, -5);
}

// Tile b kept an edge that starts at tile a's joint (its from_joint cut to -1): linked again.
TEST(MergeScenes, LinksCutEdgeEndsToTheJointAtTheirNode) {
    Scene b = tile(50, {10, 0}, {20, 10});
    b.roads[1].from_node = 1;  // starts at a's joint (node 1)
    const Scene m = merge_scenes({tile(1, {0, 0}, {10, 10}), b}, {"a", "b"});
    EXPECT_EQ(m.roads[3].from_joint, 0);
    EXPECT_EQ(m.joints[0].edges, (std::vector<uint32_t>{0, 3}));
    EXPECT_EQ(m.roads[1].to_joint, -1);  // a node without a joint stays without
}

// Tiles parsed with one --dem share the terrain; each one's retaining walls come along, in order.
TEST(MergeScenes, AppendsTheRetainingWalls) {
    Scene a = tile(1, {0, 0}, {10, 10}), b = tile(50, {10, 0}, {20, 10});
    for (Scene* s : {&a, &b}) s->terrain.nx = s->terrain.ny = 2, s->terrain.cell = 20, s->terrain.heights = {0, 1, 2, 3};
    RetainingWall w;
    w.osm = {OsmType::Way, 7}, w.line = {{1, 1}, {5, 1}};
    a.retaining_walls = {w};
    w.osm.id = 8, w.line = {{11, 1}, {15, 1}, {15, 5}};
    b.retaining_walls = {w, w};
    b.retaining_walls[1].osm.id = 9;
    const Scene m = merge_scenes({std::move(a), std::move(b)}, {"a", "b"});
    ASSERT_EQ(m.retaining_walls.size(), 3u);
    EXPECT_EQ(m.retaining_walls[0].osm.id, 7);
    EXPECT_EQ(m.retaining_walls[1].osm.id, 8);
    EXPECT_EQ(m.retaining_walls[1].line.size(), 3u);
    EXPECT_EQ(m.retaining_walls[2].osm.id, 9);
}

TEST(MergeScenes, OneSceneIsUntouched) {
    const Scene m = merge_scenes({tile(1, {0, 0}, {10, 10})}, {"a"});
    EXPECT_EQ(m.roads[1].from_joint, -1);
    EXPECT_EQ(m.joints[0].edges, std::vector<uint32_t>{0});
}

std::string refusal(Scene b) {
    try {
        merge_scenes({tile(1, {0, 0}, {10, 10}), std::move(b)}, {"a.scene", "b.scene"});
    } catch (const Error& e) {
        return e.what();
    }
    return "";
}

TEST(MergeScenes, RefusesScenesOfAnotherFrameSeedOrTerrain) {
    Scene b = tile(50, {10, 0}, {20, 10});
    b.header.origin_lon = 7.9;
    EXPECT_EQ(refusal(b), "b.scene: origin 49.4,7.9 (transverse-mercator) is not a.scene's 49.4,7.8 "
                          "(transverse-mercator); parse the tiles with one --origin");
    b = tile(50, {10, 0}, {20, 10});
    b.header.projection = "utm";
    EXPECT_NE(refusal(b).find("parse the tiles with one --origin"), std::string::npos);
    b = tile(50, {10, 0}, {20, 10});
    b.header.seed = 2;
    EXPECT_EQ(refusal(b), "b.scene: seed 2 is not a.scene's 1; parse the tiles with one --seed");
    b = tile(50, {10, 0}, {20, 10});
    b.terrain.nx = b.terrain.ny = 2, b.terrain.cell = 1, b.terrain.heights = {0, 0, 0, 0};
    EXPECT_NE(refusal(b).find("different terrain (--dem) cannot be merged"), std::string::npos);
}

}  // namespace
