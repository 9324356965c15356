// Tile scenes merged into one: indices between lists moved with them, edge ends a tile cut from
// their joint linked again, the tiles' terrain joined, and scenes that do not share a frame, seed
// or terrain grid refused.
#include <cmath>

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
    EXPECT_EQ(refusal(b), "a.scene has no terrain and b.scene has; parse every tile with the same --dem");
}

// A field of nx x ny nodes from lattice node (i0, j0), 10 m apart, heights `reference` + base + i + 100 j.
HeightField field(int64_t i0, int64_t j0, uint32_t nx, uint32_t ny, double reference, float base) {
    HeightField f;
    f.origin = {i0 * 10.0, j0 * 10.0};
    f.cell = 10;
    f.nx = nx, f.ny = ny;
    f.reference_altitude = reference;
    f.vertical_datum = "EGM96 geoid";
    for (uint32_t j = 0; j < ny; ++j)
        for (uint32_t i = 0; i < nx; ++i) f.heights.push_back(base + float(i0 + i) + 100.0f * float(j0 + j));
    return f;
}

Scene tile_on(HeightField terrain) {
    Scene s = tile(1, {0, 0}, {10, 10});
    s.terrain = std::move(terrain);
    return s;
}

// The altitude of node (i, j) of the merged field.
double altitude(const HeightField& f, int64_t i, int64_t j) {
    const int64_t i0 = std::llround(f.origin.x / f.cell), j0 = std::llround(f.origin.y / f.cell);
    return f.reference_altitude + f.heights[static_cast<size_t>((j - j0) * f.nx + (i - i0))];
}

// Tiles parsed with one --dem-resolution: one field over both, each node from the tile it lies
// deepest inside (the one whose core holds it), altitudes kept whatever each tile's reference.
TEST(MergeScenes, JoinsTheTilesTerrainEachNodeFromTheTileItLiesDeepestIn) {
    // a: nodes 0..10 x 0..6 at 1,000 m + i + 100 j; b: nodes 6..16 x 0..6 at 5,000 m + ..., a lower reference.
    const Scene merged = merge_scenes({tile_on(field(0, 0, 11, 7, 300, 700)), tile_on(field(6, 0, 11, 7, 200, 4800))},
                                      {"a.scene", "b.scene"});
    const HeightField& f = merged.terrain;
    EXPECT_EQ(f.origin.x, 0);
    EXPECT_EQ(f.origin.y, 0);
    EXPECT_EQ(f.nx, 17u);
    EXPECT_EQ(f.ny, 7u);
    EXPECT_EQ(f.reference_altitude, 200);
    EXPECT_EQ(f.vertical_datum, "EGM96 geoid");
    for (int64_t j = 0; j < 7; ++j) {
        for (int64_t i = 0; i <= 16; ++i) {
            const double from_a = 1000 + i + 100 * j, from_b = 5000 + i + 100 * j;
            if (i <= 5) {
                EXPECT_EQ(altitude(f, i, j), from_a) << i << "," << j;  // a alone
            } else if (i >= 11) {
                EXPECT_EQ(altitude(f, i, j), from_b) << i << "," << j;  // b alone
            }
        }
    }
    // The overlap, on the middle row: a is deeper up to node 8 (a tie: the first tile), b beyond.
    for (int64_t i = 6; i <= 10; ++i) EXPECT_EQ(altitude(f, i, 3), (i <= 8 ? 1000 : 5000) + i + 300) << i;
}

TEST(MergeScenes, AGapBetweenTilesTakesTheNearestTilesEdge) {
    // a: rows 0..3, b: rows 6..9, both over columns 0..3: rows 4 and 5 are nobody's.
    const Scene merged = merge_scenes({tile_on(field(0, 0, 4, 4, 0, 0)), tile_on(field(0, 6, 4, 4, 0, 0))},
                                      {"a.scene", "b.scene"});
    const HeightField& f = merged.terrain;
    ASSERT_EQ(f.ny, 10u);
    for (int64_t i = 0; i < 4; ++i) {
        EXPECT_EQ(altitude(f, i, 4), i + 300);  // a's top row
        EXPECT_EQ(altitude(f, i, 5), i + 600);  // b's bottom row
    }
}

TEST(MergeScenes, RefusesTerrainOnAnotherGrid) {
    auto refused = [](HeightField b) {
        try {
            merge_scenes({tile_on(field(0, 0, 4, 4, 0, 0)), tile_on(std::move(b))}, {"a.scene", "b.scene"});
        } catch (const Error& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    HeightField b = field(2, 0, 4, 4, 0, 0);
    b.cell = 20;
    EXPECT_NE(refused(b).find("parse the tiles with one --dem-resolution"), std::string::npos) << refused(b);
    b = field(2, 0, 4, 4, 0, 0);
    b.vertical_datum = "WGS84 ellipsoid";
    EXPECT_NE(refused(b).find("b.scene: terrain heights above WGS84 ellipsoid"), std::string::npos) << refused(b);
    b = field(2, 0, 4, 4, 0, 0);
    b.origin.x = 25;
    EXPECT_NE(refused(b).find("not on multiples of the cell"), std::string::npos) << refused(b);
    EXPECT_EQ(refused(HeightField{}), "b.scene has no terrain and a.scene has; parse every tile with the same --dem");
}

}  // namespace
