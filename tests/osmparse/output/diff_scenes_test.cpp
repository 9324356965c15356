// --diff's comparison: objects matched by OSM identity, changes beyond the tolerance reported.
#include <gtest/gtest.h>

#include "osmparse/output/diff_scenes.h"

using namespace citygen;

namespace {

RetainingWall wall(int64_t way, std::vector<Vec2> line, double height) {
    RetainingWall w;
    w.osm = {OsmType::Way, way};
    w.line = std::move(line);
    w.height = height;
    return w;
}

std::string changes_text(const std::vector<SceneChange>& changes) {
    std::string text;
    for (const SceneChange& c : changes) text += c.what + " " + c.object + ": " + c.detail + "\n";
    return text;
}

// Wall 1 the same within the tolerance, wall 2 moved, 3 taller, 4 of another material, 5 gone, 6 new.
TEST(DiffScenes, ComparesRetainingWalls) {
    Scene a, b;
    a.retaining_walls = {wall(1, {{0, 0}, {10, 0}}, 2), wall(2, {{0, 5}, {10, 5}}, 2), wall(3, {{0, 9}, {9, 9}}, 2),
                         wall(4, {{0, 12}, {8, 12}}, 2), wall(5, {{0, 20}, {5, 20}}, 2)};
    b.retaining_walls = a.retaining_walls;
    b.retaining_walls[0].line[1].x += 0.005;
    b.retaining_walls[1].line[0].y += 0.5;
    b.retaining_walls[2].height = 3;
    b.retaining_walls[3].material = WallMaterial::Stone;
    b.retaining_walls[4] = wall(6, {{0, 30}, {5, 30}}, 2);
    const std::vector<SceneChange> changes = diff_scenes(a, b, 0.01);
    EXPECT_EQ(changes_text(changes),
              "changed retaining_wall w2#0: line moved 0.500 m\n"
              "changed retaining_wall w3#0: height changed by 1.000 m\n"
              "changed retaining_wall w4#0: material concrete -> stone\n"
              "removed retaining_wall w5#0: \n"
              "added retaining_wall w6#0: \n");
    EXPECT_TRUE(diff_scenes(a, a, 0).empty());
}

}  // namespace
