// Writes the hostile scene files of tests/hostile/run_hostile.sh into a directory: scenes that
// encode_scene accepts (it checks nothing) and that the loader or the renderer must refuse.
// Usage: make_hostile_scenes DIR
#include <cmath>
#include <cstdio>
#include <string>

#include "common/scene_io.h"

using namespace citygen;

namespace {

Building box(double x0, double y0, double x1, double y1, double height) {
    Building b;
    b.osm = {OsmType::Way, 1};
    b.outer = {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
    b.height = height;
    return b;
}

Scene scene_of(Building b) {
    Scene s;
    s.header.source = "hostile";
    s.ground.min = {-100, -100};
    s.ground.max = {100, 100};
    s.buildings.push_back(box(20, 20, 40, 30, 12));  // an ordinary neighbour
    s.buildings.push_back(std::move(b));
    return s;
}

void write(const std::string& dir, const std::string& name, const Scene& s) {
    save_scene(s, dir + "/" + name + ".scene");
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: make_hostile_scenes DIR\n");
        return 2;
    }
    const std::string dir = argv[1];
    Building b = box(0, 0, 10, 10, 10);
    b.outer = {{0, 0}, {5, 0}, {10, 0}, {3, 0}};
    write(dir, "collinear_outline", scene_of(b));
    b.outer = {{7, 7}, {7, 7}, {7, 7}, {7, 7}};
    write(dir, "identical_points", scene_of(b));
    write(dir, "coordinates_1e30", scene_of(box(1e30, 1e30, 1e30 + 1e24, 1e30 + 1e24, 10)));
    write(dir, "coordinates_1e7", scene_of(box(-1e7, -1e7, 1e7, 1e7, 10)));
    write(dir, "height_1e6", scene_of(box(0, 0, 10, 10, 1e6)));
    b = box(0, 0, 10, 10, 10);
    b.outer.clear();
    for (int i = 0; i < 100000; ++i) b.outer.push_back({50 * std::cos(i * 2 * kPi / 100000), 50 * std::sin(i * 2 * kPi / 100000)});
    write(dir, "points_100k", scene_of(b));
    // Within every limit, but the stored facades of 100 blocks of 9 km, 1000 m tall, need
    // about 2.4 TB, more than any test machine has: the memory estimate must refuse it.
    Scene big = scene_of(box(-4500, -4500, 4500, 4500, 1000));
    for (int i = 1; i < 100; ++i) {
        big.buildings.push_back(box(-4500, -4500 + 10000.0 * i, 4500, 4500 + 10000.0 * i, 1000));
        big.buildings.back().osm.id = 1 + i;
    }
    write(dir, "too_big_to_fit", big);
    return 0;
}
