// Scene format 1.1: the map's content survives a round trip, and bad indices or values in the
// new tables are refused with a clear message.
#include <gtest/gtest.h>

#include "common/error.h"
#include "common/scene_io.h"

using namespace citygen;

namespace {

Scene sample() {
    Scene s;
    RoadEdge r;
    r.osm = {OsmType::Way, 7};
    r.centreline = {{0, 0}, {50, 0}};
    r.quad = {{0, -3}, {50, -3}, {50, 3}, {0, 3}};
    r.width = 6;
    r.lanes_forward = 2;
    r.lanes_backward = 1;
    r.centre_line = CentreLine::Solid;
    r.edge_lines = true;
    r.cycle_lane_right = true;
    s.roads.push_back(r);
    s.land_cover.push_back({{OsmType::Relation, 3}, LandCoverClass::Water,
                            {{0, 0}, {10, 0}, {10, 10}, {0, 10}}, {{{2, 2}, {2, 4}, {4, 4}, {4, 2}}}});
    Tree t;
    t.osm = {OsmType::Node, 11};
    t.position = {5, 6};
    t.height = 12;
    t.crown_diameter = 5;
    t.leaf_type = LeafType::Needleleaved;
    t.source = TreeSource::Scattered;
    s.trees.push_back(t);
    PathEdge p;
    p.osm = {OsmType::Way, 9};
    p.centreline = {{0, 10}, {20, 10}};
    p.quad = {{0, 9}, {20, 9}, {20, 11}, {0, 11}};
    p.width = 2;
    p.path_class = PathClass::Cycleway;
    p.sidewalk = true;
    s.paths.push_back(p);
    s.crossings.push_back({{OsmType::Node, 12}, 0, {25, 0}, CrossingKind::Zebra, RoadSide::Both});
    return s;
}

}  // namespace

TEST(SceneFormat11, NewTablesRoundTrip) {
    const Scene s = sample();
    const std::vector<uint8_t> bytes = encode_scene(s);
    const Scene back = decode_scene(bytes.data(), bytes.size(), "sample");
    EXPECT_EQ(back.header.format_minor, kSceneFormatMinor);
    ASSERT_EQ(back.roads.size(), 1u);
    EXPECT_EQ(back.roads[0].lanes_forward, 2);
    EXPECT_EQ(back.roads[0].centre_line, CentreLine::Solid);
    EXPECT_TRUE(back.roads[0].cycle_lane_right);
    ASSERT_EQ(back.land_cover.size(), 1u);
    EXPECT_EQ(back.land_cover[0].cover, LandCoverClass::Water);
    EXPECT_EQ(back.land_cover[0].holes.size(), 1u);
    ASSERT_EQ(back.trees.size(), 1u);
    EXPECT_EQ(back.trees[0].osm, (OsmRef{OsmType::Node, 11}));
    EXPECT_EQ(back.trees[0].leaf_type, LeafType::Needleleaved);
    EXPECT_EQ(back.trees[0].source, TreeSource::Scattered);
    EXPECT_DOUBLE_EQ(back.trees[0].height, 12);
    ASSERT_EQ(back.paths.size(), 1u);
    EXPECT_EQ(back.paths[0].path_class, PathClass::Cycleway);
    EXPECT_TRUE(back.paths[0].sidewalk);
    ASSERT_EQ(back.crossings.size(), 1u);
    EXPECT_EQ(back.crossings[0].road, 0);
    EXPECT_EQ(encode_scene(back), bytes);
}

TEST(SceneFormat11, BadIndicesAndSizesAreRefused) {
    auto refused = [](const Scene& s, const std::string& words) {
        const std::vector<uint8_t> bytes = encode_scene(s);
        try {
            decode_scene(bytes.data(), bytes.size(), "bad.scene");
        } catch (const Error& e) {
            EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
            return;
        }
        ADD_FAILURE() << "accepted a scene with " << words;
    };
    Scene s = sample();
    s.crossings[0].road = 5;
    refused(s, "crossing road index out of range");
    s = sample();
    s.land_cover[0].holes[0] = {{2, 2}, {3, 3}, {4, 4}};  // collinear: no area
    refused(s, "land cover hole has zero area");
    s = sample();
    Building b;
    b.outer = {{0, 0}, {10, 0}, {10, 10}, {0, 10}};
    b.height = 10;
    RoofFace face;
    face.points = {{0, 0, 10}, {20000, 0, 10}, {0, 10, 10}};  // 20 km across
    b.roof_faces.push_back(face);
    s.buildings.push_back(b);
    refused(s, "roof face is over");
    s = sample();
    s.trees[0].height = -1;
    refused(s, "tree height");
    s = sample();
    s.paths[0].from_joint = 3;
    refused(s, "path joint index 3 out of range");
    s = sample();
    s.path_joints.push_back({{OsmType::Node, 1}, {{0, 0}, {1, 0}, {1, 1}}, {4}});
    refused(s, "path joint edge index 4 out of range");
}
