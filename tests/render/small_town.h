// The small test town of the render tests (a courtyard block, a tower, a road and a sidewalk),
// settings for tiny renders of it, and per-channel statistics of a film.
#pragma once

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "common/scene.h"
#include "render/camera/camera.h"
#include "render/film/render_image.h"
#include "render/materials/materials.h"

namespace citygen::test {

inline Ring square(double x0, double y0, double size) {
    return {{x0, y0}, {x0 + size, y0}, {x0 + size, y0 + size}, {x0, y0 + size}};
}

// A courtyard building (concave: light bounces between its walls) and a plain block.
inline Scene small_town() {
    Scene s;
    s.header.bounds_min = {-50, -50};
    s.header.bounds_max = {50, 50};
    s.ground.min = {-50, -50};
    s.ground.max = {50, 50};
    Building courtyard;
    courtyard.outer = square(-20, -20, 30);
    Ring hole = square(-12, -12, 14);
    std::reverse(hole.begin(), hole.end());
    courtyard.holes.push_back(hole);
    courtyard.height = 18;
    s.buildings.push_back(courtyard);
    Building block;
    block.outer = square(15, 5, 10);
    block.height = 30;
    s.buildings.push_back(block);
    RoadEdge road;
    road.quad = {{-50, -30}, {50, -30}, {50, -24}, {-50, -24}};
    s.roads.push_back(road);
    Sidewalk walk;
    walk.polygon = {{-50, -24}, {50, -24}, {50, -22}, {-50, -22}};
    s.sidewalks.push_back(walk);
    return s;
}

inline MaterialTable all_white_diffuse() {
    MaterialTable m = default_materials();
    for (Material& x : m) x = Material{"white", MaterialType::Diffuse, {1, 1, 1}, {0, 0, 0}, 1, 1.5, {}};
    return m;
}

inline RenderSettings tiny(int spp) {
    RenderSettings r;
    r.width = 24;
    r.height = 16;
    r.spp = spp;
    r.quiet = true;
    r.integrator.max_depth = 1000;
    r.integrator.rr_depth = 1000;  // no roulette: every path carries exactly its throughput
    return r;
}

inline Camera view_of_town(const RenderSettings& r) {
    return Camera::look_at({-60, -70, 45}, {0, 0, 5}, 60, r.width, r.height);
}

struct ChannelStats {
    double mean = 0, standard_error = 0, min = 1e30, max = -1e30;
};

inline ChannelStats stats_of(const Film& film, int channel) {
    ChannelStats s;
    const size_t n = film.rgb.size() / 3;
    double sum = 0, sum2 = 0;
    for (size_t i = 0; i < n; ++i) {
        const double v = film.rgb[3 * i + channel];
        sum += v;
        sum2 += v * v;
        s.min = std::min(s.min, v);
        s.max = std::max(s.max, v);
    }
    s.mean = sum / n;
    s.standard_error = std::sqrt(std::max(0.0, sum2 / n - s.mean * s.mean) / n);
    return s;
}

// Every pixel of every channel within 0.01 of one (white furnace tests).
inline void expect_all_one(const Film& film) {
    for (int c = 0; c < 3; ++c) {
        const ChannelStats s = stats_of(film, c);
        EXPECT_NEAR(s.min, 1.0, 0.01) << "channel " << c;
        EXPECT_NEAR(s.max, 1.0, 0.01) << "channel " << c;
    }
}

}  // namespace citygen::test
