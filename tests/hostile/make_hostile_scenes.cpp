// Writes the hostile scene files of tests/hostile/run_hostile.sh into a directory: scenes that
// encode_scene accepts (it checks nothing) and that the loader or the renderer must refuse.
// Usage: make_hostile_scenes DIR          (every scene)
//        make_hostile_scenes DIR HOLES    (only courtyards_HOLES.scene, to measure growth)
#include <cmath>
#include <cstdio>
#include <cstdlib>
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

// One building of `holes` square courtyards (1 m, on a 3 m grid, clockwise), every ring within
// the limits: the cost of everything the renderer sets up per building must not grow with the
// square of its rings.
Scene courtyards(int holes) {
    const int side = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(holes))));
    Building b = box(-1.5 * side - 1, -1.5 * side - 1, 1.5 * side + 1, 1.5 * side + 1, 10);
    for (int i = 0; i < holes; ++i) {
        const double x = -1.5 * side + 3.0 * (i % side) + 1, y = -1.5 * side + 3.0 * (i / side) + 1;
        b.holes.push_back({{x, y}, {x, y + 1}, {x + 1, y + 1}, {x + 1, y}});
    }
    Scene s = scene_of(std::move(b));
    s.buildings.front().outer = box(1.5 * side + 20, 0, 1.5 * side + 40, 10, 12).outer;
    s.ground.min = {-1.5 * side - 100, -1.5 * side - 100};
    s.ground.max = {1.5 * side + 100, 1.5 * side + 100};
    return s;
}

void write(const std::string& dir, const std::string& name, const Scene& s) {
    save_scene(s, dir + "/" + name + ".scene");
}

}  // namespace

int main(int argc, char** argv) {
    if (argc != 2 && argc != 3) {
        std::fprintf(stderr, "usage: make_hostile_scenes DIR [HOLES]\n");
        return 2;
    }
    const std::string dir = argv[1];
    if (argc == 3) {
        const int holes = std::atoi(argv[2]);
        write(dir, "courtyards_" + std::to_string(holes), courtyards(holes));
        return 0;
    }
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
    write(dir, "courtyards_100k", courtyards(100000));
    return 0;
}
