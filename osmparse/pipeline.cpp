// osmparse from top to bottom: each stage is a function from data to data.
#include "pipeline.h"

#include <chrono>

#include "assemble_sea.h"
#include "build_buildings.h"
#include "build_land_cover.h"
#include "build_paths.h"
#include "lay_out_lanes.h"
#include "build_road_graph.h"
#include "build_road_polygons.h"
#include "build_sidewalks.h"
#include "narrow_roads.h"
#include "place_lamps.h"
#include "place_trees.h"
#include "projection.h"
#include "read_osm.h"

namespace citygen {

namespace {

// Times one stage and records it in the report.
template <typename F>
auto timed(ParseReport& report, const char* stage, F&& f) {
    const auto start = std::chrono::steady_clock::now();
    auto result = f();
    report.stage_time(stage, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    return result;
}

std::string base_name(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

// The origin is the centre of the data's bounding box, so coordinates stay small.
Projection projection_for(const OsmData& osm) {
    if (osm.min.lat > osm.max.lat) {  // nothing located but perhaps coastline: the extract's centre
        if (osm.has_extract_bounds)
            return Projection(0.5 * (osm.extract_min.lat + osm.extract_max.lat),
                              0.5 * (osm.extract_min.lon + osm.extract_max.lon));
        return Projection(0, 0);
    }
    return Projection(0.5 * (osm.min.lat + osm.max.lat), 0.5 * (osm.min.lon + osm.max.lon));
}

SceneHeader make_header(const ParseJob& job, const Projection& projection) {
    SceneHeader h;
    h.generator = std::string("citygen osmparse ") + CITYGEN_VERSION;
    h.origin_lat = projection.origin_lat();
    h.origin_lon = projection.origin_lon();
    h.projection = Projection::name();
    h.seed = job.params.seed;
    h.options = job.params.to_key_values();
    h.source = base_name(job.input);
    return h;
}

// Bounds of everything in the scene, and a ground plane a little larger.
void set_bounds_and_ground(Scene& scene) {
    Box2 box;
    for (const Building& b : scene.buildings) for (Vec2 p : b.outer) box.extend(p);
    for (const RoadEdge& r : scene.roads) for (Vec2 p : r.quad) box.extend(p);
    for (const Joint& j : scene.joints) for (Vec2 p : j.polygon) box.extend(p);
    for (const Sidewalk& s : scene.sidewalks) for (Vec2 p : s.polygon) box.extend(p);
    for (const Lamp& l : scene.lamps) box.extend({l.position.x, l.position.y});
    if (box.empty()) box.extend({0, 0});
    scene.header.bounds_min = box.min;
    scene.header.bounds_max = box.max;
    constexpr double kGroundMargin = 50;  // metres of ground beyond the data on each side
    scene.ground.min = box.min - Vec2(kGroundMargin, kGroundMargin);
    scene.ground.max = box.max + Vec2(kGroundMargin, kGroundMargin);
    scene.ground.z = 0;
}

}  // namespace

Scene parse_osm_to_scene(const ParseJob& job, ParseReport& report) {
    const OsmData osm = timed(report, "read", [&] { return read_osm(job.input, job.quiet, report); });
    const Projection projection = projection_for(osm);

    Scene scene;
    scene.header = make_header(job, projection);
    scene.buildings = timed(report, "buildings", [&] {
        return build_buildings(osm, projection, job.params.buildings, report);
    });
    const RoadGraph road_graph = timed(report, "road graph", [&] {
        return build_road_graph(osm, projection, job.params.roads, report);
    });
    const RoadGraph narrowed_graph = timed(report, "roads vs buildings", [&] {
        return narrow_roads(road_graph, scene.buildings, job.params.roads, report);
    });
    RoadSurface surface = timed(report, "road polygons", [&] {
        return build_road_polygons(narrowed_graph, job.params.roads, report);
    });
    scene.roads = surface.roads;
    scene.joints = surface.joints;
    lay_out_lanes(scene.roads, osm, report);
    scene.sidewalks = timed(report, "sidewalks", [&] {
        return build_sidewalks(narrowed_graph, surface, scene.buildings, job.params.sidewalks,
                               job.params.roads.miter_limit, report);
    });
    PathSurface paths = timed(report, "paths and rails", [&] {
        return build_paths(osm, projection, job.params.roads, report);
    });
    scene.sidewalks = drop_doubled_sidewalks(std::move(scene.sidewalks), paths.paths, report);
    scene.paths = std::move(paths.paths);
    scene.path_joints = std::move(paths.joints);
    scene.lamps = timed(report, "street lamps", [&] {
        return place_lamps(osm, projection, scene, job.params.lamps, job.params.seed, report);
    });
    scene.land_cover = timed(report, "land cover", [&] {
        std::vector<LandCover> cover = build_land_cover(osm, projection, job.params.buildings, report);
        std::vector<LandCover> sea =
            assemble_sea(osm, projection, extract_box(osm, projection), scene.buildings, report);
        cover.insert(cover.end(), std::make_move_iterator(sea.begin()), std::make_move_iterator(sea.end()));
        return cover;
    });
    scene.trees = timed(report, "trees", [&] {
        return place_trees(osm, projection, scene, job.params.trees, job.params.seed, report);
    });
    scene.crossings = timed(report, "crossings", [&] { return place_crossings(osm, projection, scene, report); });
    set_bounds_and_ground(scene);
    return scene;
}

}  // namespace citygen
