// A view of a whole scene tens of km across: the haze over the ground must meet the sky
// without a dark line. The ground plane ends (far, but not at infinity): camera rays that pass
// just over its edge, still below the horizon, once saw the sky's darkened below-horizon colour
// instead of the haze the ground would have shown there.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "render/camera/camera.h"
#include "render/film/render_image.h"
#include "render/geometry/build_render_scene.h"
#include "render/lights/sky.h"
#include "render/materials/materials.h"

using namespace citygen;

namespace {

// Four small blocks at the corners of a square `side` metres across, nothing between.
Scene wide_scene(double side) {
    Scene s;
    const double h = side / 2;
    s.header.bounds_min = {-h, -h};
    s.header.bounds_max = {h, h};
    s.ground.min = s.header.bounds_min;
    s.ground.max = s.header.bounds_max;
    int64_t id = 1;
    for (double x : {-h, h - 20})
        for (double y : {-h, h - 20}) {
            Building b;
            b.osm = {OsmType::Way, id++};
            b.outer = {{x, y}, {x + 20, y}, {x + 20, y + 20}, {x, y + 20}};
            b.height = 15;
            s.buildings.push_back(b);
        }
    return s;
}

// Mean luminance of each image row, top first.
std::vector<double> row_luminance(const Film& film) {
    std::vector<double> rows(film.height, 0.0);
    for (int y = 0; y < film.height; ++y) {
        for (int x = 0; x < film.width; ++x) {
            const float* p = &film.rgb[3 * (static_cast<size_t>(y) * film.width + x)];
            rows[y] += 0.2126 * p[0] + 0.7152 * p[1] + 0.0722 * p[2];
        }
        rows[y] /= film.width;
    }
    return rows;
}

void expect_no_dark_line(GeometryMode mode, TimeOfDay time, double side) {
    const Scene scene = wide_scene(side);
    const auto render_scene = build_render_scene(scene, GeometryModes::all(mode));
    const MaterialTable materials = default_materials();
    const Sky sky = Sky::for_settings(SkySettings{time});
    RenderSettings settings;
    settings.width = 96;
    settings.height = 54;
    settings.spp = 2;
    settings.quiet = true;
    settings.integrator.haze_extinction = 3.912 / 20000;  // render's default 20 km visibility
    const PathContext context{*render_scene, materials, sky, settings.integrator};
    // The whole square from the south-west, 20 degrees down (as the automatic view framed a
    // whole scene before it looked at the densest part only).
    const double pitch = 20 * M_PI / 180;
    const Vec2 from = normalize(Vec2{-1, -1.6});
    const Vec3 back{from.x * std::cos(pitch), from.y * std::cos(pitch), std::sin(pitch)};
    const Camera camera = Camera::look_at(back * (1.2 * side), {0, 0, 0}, 50, settings.width, settings.height);
    const Film film = render_image(context, camera, settings);
    const std::vector<double> rows = row_luminance(film);
    // Over the haze and the sky the rows change smoothly; a line is a row darker than both of
    // its neighbours (the line was 30-70% darker; sample noise here is below 1%).
    std::string profile;
    for (double r : rows) profile += " " + std::to_string(r).substr(0, 7);
    for (int y = 1; y + 1 < film.height; ++y)
        EXPECT_GE(rows[y], 0.97 * std::min(rows[y - 1], rows[y + 1]))
            << "row " << y << " of " << film.height << " (" << to_string(mode) << ", " << side / 1000
            << " km); rows:" << profile;
}

}  // namespace

TEST(Horizon, NoDarkLineBetweenHazeAndSkyStored) {
    expect_no_dark_line(GeometryMode::Stored, TimeOfDay::Day, 36000);
}

TEST(Horizon, NoDarkLineBetweenHazeAndSkyProcedural) {
    expect_no_dark_line(GeometryMode::Procedural, TimeOfDay::Day, 36000);
}

TEST(Horizon, NoDarkLineAtSunsetOrOnASmallerScene) {
    expect_no_dark_line(GeometryMode::Stored, TimeOfDay::Sunset, 36000);
    expect_no_dark_line(GeometryMode::Stored, TimeOfDay::Day, 8000);
}
