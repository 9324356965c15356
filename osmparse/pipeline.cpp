// osmparse from top to bottom: each stage is a function from data to data. The stage numbers in
// the headers follow this file: 1 read, 2 buildings, 3 heights, 4 roofs, 5 colours, 6 road graph,
// 7 roads vs buildings, 8 road polygons, 9 lanes, 10 sidewalks, 11 paths and rails, 12 empty
// blocks (optional), 13 street lamps, 14 land cover and sea, 15 trees, 16 crossings. One
// exception, for peak memory (see run_pipeline): roofs and colours (4, 5), which no other
// stage reads, run last (or just before the empty blocks, 12, when those are filled).
#include "osmparse/pipeline.h"

#include <algorithm>
#include <chrono>
#include <functional>
#include <memory>
#include <optional>

#ifdef __GLIBC__
#include <malloc.h>
#endif

#include <tbb/task_arena.h>
#include <tbb/task_group.h>

#include "common/rng.h"
#include "common/scene_io.h"
#include "osmparse/buildings/build_buildings.h"
#include "osmparse/buildings/building_colours.h"
#include "osmparse/buildings/building_tags.h"
#include "osmparse/buildings/infer_heights.h"
#include "osmparse/core/projection.h"
#include "osmparse/map/assemble_sea.h"
#include "osmparse/map/build_land_cover.h"
#include "osmparse/map/fill_empty_blocks.h"
#include "osmparse/map/place_lamps.h"
#include "osmparse/map/place_trees.h"
#include "osmparse/read/read_osm.h"
#include "osmparse/roads/build_paths.h"
#include "osmparse/roads/build_road_graph.h"
#include "osmparse/roads/build_road_polygons.h"
#include "osmparse/roads/build_sidewalks.h"
#include "osmparse/roads/lay_out_lanes.h"
#include "osmparse/roads/narrow_roads.h"
#include "osmparse/roofs/build_roofs.h"

namespace citygen {

namespace {

// Frees a vector whose last reader is done, so later stages can reuse its memory.
template <typename T>
void release(std::vector<T>& v) {
    std::vector<T>().swap(v);
}

// Times one stage and records it in the report.
template <typename F>
auto timed(ParseReport& report, const char* stage, F&& f) {
    const auto start = std::chrono::steady_clock::now();
    auto result = f();
    report.stage_time(stage, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    return result;
}

// Runs groups of stages side by side (TBB), each reporting into a report of its own, merged into
// `report` in the order given: the printed report is the one a run on one thread prints. The
// groups below name their parameter `report` on purpose: it hides the shared one, so no group
// can write to it while others run.
void side_by_side(ParseReport& report, const std::vector<std::function<void(ParseReport&)>>& groups) {
    std::vector<ParseReport> reports(groups.size());
    tbb::task_group tasks;
    for (size_t i = 1; i < groups.size(); ++i) tasks.run([&, i] { groups[i](reports[i]); });
    groups.front()(reports.front());  // on this thread
    tasks.wait();
    for (const ParseReport& r : reports) report.merge(r);
}

std::string base_name(const std::string& path) {
    const size_t slash = path.find_last_of('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

// Calls f(LatLon) for every location of the town: buildings, highways (roads and paths) and
// lamps (the read stage's bounds also take in the tree rows).
template <typename F>
void for_each_town_location(const OsmData& osm, F&& f) {
    for (const OsmArea& a : osm.building_areas)
        for (const OsmPolygon& p : a.polygons)
            for (const LatLon& l : p.outer) f(l);
    for (const OsmWay& w : osm.highways)
        for (const LatLon& l : w.locations) f(l);
    for (const OsmNode& n : osm.street_lamps) f(n.location);
}

// Calls f(LatLon) for every other location that can reach the scene: tree rows, land cover,
// trees, crossings, rails, and the coastline as far as the sea is clipped to (the extract's box,
// see extract_box; none without one).
template <typename F>
void for_each_map_location(const OsmData& osm, F&& f) {
    for (const OsmWay& w : osm.tree_rows)
        for (const LatLon& l : w.locations) f(l);
    for (const OsmArea& a : osm.land_cover_areas)
        for (const OsmPolygon& p : a.polygons)
            for (const LatLon& l : p.outer) f(l);
    for (const OsmNode& n : osm.trees) f(n.location);
    for (const OsmNode& n : osm.road_marks) f(n.location);
    for (const OsmWay& w : osm.railways)
        for (const LatLon& l : w.locations) f(l);
    const LatLon lo = osm.has_extract_bounds ? osm.extract_min : osm.min;
    const LatLon hi = osm.has_extract_bounds ? osm.extract_max : osm.max;
    if (lo.lat <= hi.lat && lo.lon <= hi.lon)
        for (const OsmWay& w : osm.coastlines)
            for (const LatLon& l : w.locations)
                f(LatLon{std::clamp(l.lat, lo.lat, hi.lat), std::clamp(l.lon, lo.lon, hi.lon)});
}

// The median of the locations, per axis.
LatLon median_location(std::vector<double> lats, std::vector<double> lons) {
    const size_t mid = lats.size() / 2;
    std::nth_element(lats.begin(), lats.begin() + mid, lats.end());
    std::nth_element(lons.begin(), lons.begin() + mid, lons.end());
    return {lats[mid], lons[mid]};
}

// The origin is the centre of the box of the town's locations (the read stage's bounds), so
// coordinates stay small; where the extract has no town (a nature reserve, a lake), of
// everything else located. Data spanning more than a degree is a region, or a city with a stray
// node far away (a mapping mistake): then the median location, which a few strays cannot move
// out of town (what lies beyond the scene limits is dropped or clipped).
Projection projection_for(const OsmData& osm) {
    const bool town = osm.min.lat <= osm.max.lat;
    std::vector<double> lats, lons;
    auto add = [&](const LatLon& l) {
        lats.push_back(l.lat);
        lons.push_back(l.lon);
    };
    if (town) for_each_town_location(osm, add);
    else for_each_map_location(osm, add);
    if (!town && lats.empty()) {  // nothing located: the extract's centre
        if (osm.has_extract_bounds)
            return Projection(0.5 * (osm.extract_min.lat + osm.extract_max.lat),
                              0.5 * (osm.extract_min.lon + osm.extract_max.lon));
        return Projection(0, 0);
    }
    LatLon min = osm.min, max = osm.max;
    if (!town) {
        min = {*std::min_element(lats.begin(), lats.end()), *std::min_element(lons.begin(), lons.end())};
        max = {*std::max_element(lats.begin(), lats.end()), *std::max_element(lons.begin(), lons.end())};
    }
    if ((max.lat - min.lat > 1 || max.lon - min.lon > 1) && !lats.empty()) {
        const LatLon m = median_location(std::move(lats), std::move(lons));
        return Projection(m.lat, m.lon);
    }
    return Projection(0.5 * (min.lat + max.lat), 0.5 * (min.lon + max.lon));
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

// What the scene's bounds take of the buildings: their footprints' outer rings.
void extend_by_footprints(Box2& box, const std::vector<Building>& buildings) {
    for (const Building& b : buildings) for (Vec2 p : b.outer) box.extend(p);
}

// Bounds of everything in the scene, and a ground plane a little larger. `box`: the bounds
// of buildings already encoded and freed (parse_osm_to_file), or empty.
void set_bounds_and_ground(Scene& scene, Box2 box = {}) {
    extend_by_footprints(box, scene.buildings);
    for (const RoadEdge& r : scene.roads) for (Vec2 p : r.quad) box.extend(p);
    for (const Joint& j : scene.joints) for (Vec2 p : j.polygon) box.extend(p);
    for (const Sidewalk& s : scene.sidewalks) for (Vec2 p : s.polygon) box.extend(p);
    for (const Lamp& l : scene.lamps) box.extend({l.position.x, l.position.y});
    // And the rest of the map: a scene of a forest is framed by its forest.
    for (const LandCover& c : scene.land_cover) for (Vec2 p : c.outer) box.extend(p);
    for (const Tree& t : scene.trees) box.extend(t.position);
    for (const PathEdge& e : scene.paths) for (Vec2 p : e.quad) box.extend(p);
    for (const Joint& j : scene.path_joints) for (Vec2 p : j.polygon) box.extend(p);
    for (const Crossing& c : scene.crossings) box.extend(c.position);
    if (box.empty()) box.extend({0, 0});
    scene.header.bounds_min = box.min;
    scene.header.bounds_max = box.max;
    constexpr double kGroundMargin = 50;  // metres of ground beyond the data on each side
    scene.ground.min = box.min - Vec2(kGroundMargin, kGroundMargin);
    scene.ground.max = box.max + Vec2(kGroundMargin, kGroundMargin);
    scene.ground.z = 0;
}

// For the height benchmark (tests/bench/height_bench.sh): forget every height-like tag of a
// seeded `fraction` of the buildings, so the rules for untagged buildings can be compared with
// the truth. Height-like: every key that names a height or a level (height, min_height,
// roof:height, est_height, building:levels, building:levels:underground, roof:levels,
// building:min_level, level, ...), so no variant a rule might read later is left behind.
bool is_height_like(const std::string& key) {
    return key.find("height") != std::string::npos || key.find("level") != std::string::npos;
}

void hide_height_tags(OsmData& osm, double fraction, uint64_t seed) {
    for (OsmArea& area : osm.building_areas) {
        const uint64_t key = hash_keys(seed, 0x4849444548ull, static_cast<uint64_t>(area.ref.type),
                                       static_cast<uint64_t>(area.ref.id));
        if (hash_to_unit(key) >= fraction) continue;
        auto& entries = area.tags.entries;
        entries.erase(std::remove_if(entries.begin(), entries.end(),
                                     [](const auto& kv) { return is_height_like(kv.first); }),
                      entries.end());
    }
}

// For the roof benchmark (tests/bench/roof_bench.sh): forget the roof:shape tag of a seeded
// `fraction` of the buildings (another draw than hide_height_tags').
void hide_roof_tags(OsmData& osm, double fraction, uint64_t seed) {
    for (OsmArea& area : osm.building_areas) {
        const uint64_t key = hash_keys(seed, 0x524f4f46ull, static_cast<uint64_t>(area.ref.type),
                                       static_cast<uint64_t>(area.ref.id));
        if (hash_to_unit(key) >= fraction) continue;
        auto& entries = area.tags.entries;
        entries.erase(std::remove_if(entries.begin(), entries.end(),
                                     [](const auto& kv) { return kv.first == "roof:shape"; }),
                      entries.end());
    }
}

// Hands the pages of freed memory back to the system (see parse_osm_to_scene).
void trim_heap() {
#ifdef __GLIBC__
    malloc_trim(0);
#endif
}

// The stages in order; parse_osm_to_scene runs them on job.threads threads. With `encoder`
// (parse_osm_to_file), the buildings are encoded as soon as they are final and their roof
// faces, which no later stage reads, are freed; the rest of the scene is encoded by the caller.
Scene run_pipeline(const ParseJob& job, ParseReport& report, std::unique_ptr<SceneEncoder>* encoder) {
    OsmData osm = timed(report, "read", [&] { return read_osm(job.input, job.quiet, report); });
    if (job.hide_height_tags > 0) hide_height_tags(osm, job.hide_height_tags, job.params.seed);
    if (job.hide_roof_tags > 0) hide_roof_tags(osm, job.hide_roof_tags, job.params.seed);
    const Projection projection = projection_for(osm);

    Scene scene;
    scene.header = make_header(job, projection);
    scene.buildings = timed(report, "buildings", [&] {
        return build_buildings(osm, projection, job.params.buildings, report);
    });
    timed(report, "building heights", [&] {
        infer_heights(scene.buildings, land_use_areas(osm, projection, report), job.params.buildings, report,
                      named_buildings(osm), homes_by_use(osm));
        return 0;
    });
    // The building areas' rings are in the footprints now; the roofs and colours read only
    // some of their tags: those are kept, the areas freed.
    std::optional<BuildingTagIndex> building_tags;
    building_tags.emplace(std::move(osm.building_areas));
    // Roofs and colours change only the heights, roofs and colours of the buildings; the roads,
    // the paths and the stages after them read only the buildings' footprints (outer and holes)
    // or the OSM data. So roofs and colours run last (before the empty blocks when those are
    // filled: their buildings get roofs of their own): the roof faces (Kaiserslautern: 7 MB)
    // are then not held while another stage's working set is, only until they are encoded.
    // (They ran beside the road section before, which saved little time: build_roofs runs on
    // every thread anyway.)
    auto roofs_and_colours = [&](ParseReport& report) {
        timed(report, "roofs", [&] {
            build_roofs(scene.buildings, *building_tags, job.params.buildings, report);
            return 0;
        });
        timed(report, "colours", [&] {
            choose_colours_and_materials(scene.buildings, *building_tags, job.params.buildings, report);
            return 0;
        });
        building_tags.reset();  // their last readers are done
    };
    // The buildings are final once their roofs and colours are (and the empty blocks'
    // buildings, which have theirs, are added): encoded then, their roof faces freed.
    auto encode_buildings = [&] {
        if (!encoder) return;
        // Reserved for the scene so far (with --fill-empty-blocks, the lamps, trees, land
        // cover and crossings come later): twice its generous bound (~3x the actual size).
        // Untouched reserve costs nothing resident; a short one only a copy as it grows.
        *encoder = std::make_unique<SceneEncoder>(scene.header, 2 * encoded_size_bound(scene));
        // The encoded scene grows as the roof faces are freed: their pages go back to the
        // system every megabyte, so the two do not add up.
        size_t trimmed_at = (*encoder)->size();
        for (Building& b : scene.buildings) {
            (*encoder)->add_building(b);
            release(b.roof_faces);
            if ((*encoder)->size() > trimmed_at + (1 << 20)) {
                trim_heap();
                trimmed_at = (*encoder)->size();
            }
        }
    };
    // Without empty blocks, a building is final once it has its roof and colours: with an
    // encoder, the buildings get theirs a slice at a time, each slice encoded and its roof
    // faces freed before the next is built, so the roof faces (Kaiserslautern: 7 MB) are never
    // held all at once. Each building's roof and colours are its own (build_roofs,
    // choose_colours_and_materials): the same roofs, colours, report and bytes as all at once.
    Box2 freed_buildings_box;  // the bounds of the buildings it frees
    auto finish_buildings_in_slices = [&] {
        // Reserved before the roofs exist: the bound of the rest alone is ~2x the whole
        // encoded scene on the real extracts; a short reserve costs only a copy as it grows.
        *encoder = std::make_unique<SceneEncoder>(scene.header, 2 * encoded_size_bound(scene));
        ParseReport roofs_report, colours_report;  // merged in the order of a run all at once
        double roofs_seconds = 0, colours_seconds = 0;
        auto add_seconds = [](double& sum, auto&& f) {
            const auto start = std::chrono::steady_clock::now();
            f();
            sum += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        };
        constexpr size_t kSlice = 1024;  // buildings; build_roofs still runs on every thread
        // The buildings move into slices first and their array (2.7 MB on Kaiserslautern) is
        // freed: each slice is then freed as soon as it is encoded, while the encoded scene
        // grows, instead of the whole array waiting for the last slice.
        std::vector<std::vector<Building>> slices;
        slices.reserve((scene.buildings.size() + kSlice - 1) / kSlice);
        for (size_t begin = 0; begin < scene.buildings.size(); begin += kSlice) {
            const auto first = scene.buildings.begin() + static_cast<std::ptrdiff_t>(begin);
            const auto last = scene.buildings.begin() + static_cast<std::ptrdiff_t>(std::min(scene.buildings.size(), begin + kSlice));
            slices.emplace_back(std::make_move_iterator(first), std::make_move_iterator(last));
        }
        release(scene.buildings);
        size_t trimmed_at = (*encoder)->size();
        // The extract's roof evidence, of all the slices (as all at once).
        RoofEvidence evidence;
        for (const std::vector<Building>& slice : slices) {
            const RoofEvidence e = roof_evidence(slice, *building_tags);
            for (int g = 0; g < static_cast<int>(RoofGroup::Count); ++g) {
                evidence.tagged[g] += e.tagged[g];
                evidence.pitched[g] += e.pitched[g];
            }
        }
        for (std::vector<Building>& slice : slices) {
            add_seconds(roofs_seconds, [&] { build_roofs(slice, *building_tags, job.params.buildings, roofs_report, &evidence); });
            add_seconds(colours_seconds,
                        [&] { choose_colours_and_materials(slice, *building_tags, job.params.buildings, colours_report); });
            // Nothing reads the buildings after this but the scene's bounds: encoded, they
            // are freed (their footprints too, 4 MB on Kaiserslautern) once their extent is
            // taken. Their pages go back to the system every megabyte of encoded scene.
            extend_by_footprints(freed_buildings_box, slice);
            for (const Building& b : slice) (*encoder)->add_building(b);
            release(slice);
            if ((*encoder)->size() > trimmed_at + (1 << 20)) {
                trim_heap();
                trimmed_at = (*encoder)->size();
            }
        }
        building_tags.reset();  // their last readers are done
        report.merge(roofs_report);
        report.stage_time("roofs", roofs_seconds);
        report.merge(colours_report);
        report.stage_time("colours", colours_seconds);
    };
    auto lay_out_roads = [&](ParseReport& report) {  // the road section
        RoadGraph road_graph = timed(report, "road graph", [&] {
            return build_road_graph(osm, projection, job.params.roads, report);
        });
        NarrowedRoads narrowed = timed(report, "roads vs buildings", [&] {
            return narrow_roads(std::move(road_graph), scene.buildings, job.params.roads, report);
        });
        const RoadGraph& narrowed_graph = narrowed.graph;
        RoadSurface surface = timed(report, "road polygons", [&] {
            return build_road_polygons(narrowed_graph, std::move(narrowed.layout), report);
        });
        lay_out_lanes(surface.roads, osm, report);  // the sidewalks read no lane
        // The highways' last reader is the paths, after the sidewalks: only their ways wait.
        keep_path_ways(osm.highways);
        scene.sidewalks = timed(report, "sidewalks", [&] {
            return build_sidewalks(narrowed_graph, surface, scene.buildings, job.params.sidewalks,
                                   job.params.roads.miter_limit, report);
        });
        scene.roads = std::move(surface.roads);
        scene.joints = std::move(surface.joints);
    };  // end of the road section
    PathSurface paths;
    auto lay_out_paths = [&](ParseReport& report) {
        paths = timed(report, "paths and rails", [&] { return build_paths(osm, projection, job.params.roads, report); });
    };
    // The paths after the roads, not beside them: they are kept to the end, and would then be
    // held at the road section's peak (the sidewalks') too.
    lay_out_roads(report);
    lay_out_paths(report);
    scene.sidewalks = drop_doubled_sidewalks(std::move(scene.sidewalks), paths.paths, report);
    scene.paths = std::move(paths.paths);
    scene.path_joints = std::move(paths.joints);
    release(osm.highways);  // read by the road graph, the lanes and the paths, all done
    release(osm.railways);
    if (job.params.blocks.enabled) {
        // The blocks' own buildings have their roofs and colours: the map's get theirs first.
        roofs_and_colours(report);
        std::vector<Building> generated = timed(report, "empty blocks", [&] {
            return fill_empty_blocks(scene, job.params.buildings, job.params.blocks, job.params.sidewalks.width, report);
        });
        scene.buildings.insert(scene.buildings.end(), generated.begin(), generated.end());
        encode_buildings();
    }
    // Street lamps, land cover with the trees in it, and crossings read the scene so far and each
    // write a part of their own. The lamps first (they are placed in parallel themselves), then
    // the other two side by side: the lamps' indexes and the trees' are not held at once
    // (Kaiserslautern PBF on 2 threads: 34.5 -> 32 MB here). The report is merged in this order.
    trim_heap();  // the road section's working set is freed: its pages back first
    scene.lamps = timed(report, "street lamps", [&] {
        return place_lamps(osm, projection, scene, job.params.lamps, job.params.seed, report);
    });
    // Lamps and trees are counted as they are placed (grown by doubling); they are kept to the
    // end of the parse without the spare capacity (Kaiserslautern: 0.4 and 0.2 MB).
    scene.lamps.shrink_to_fit();
    side_by_side(report, {
        [&](ParseReport& report) {
            scene.land_cover = timed(report, "land cover", [&] {
                std::vector<LandCover> cover = build_land_cover(osm, projection, job.params.buildings, report);
                std::vector<LandCover> sea =
                    assemble_sea(osm, projection, extract_box(osm, projection), scene.buildings, report);
                cover.insert(cover.end(), std::make_move_iterator(sea.begin()), std::make_move_iterator(sea.end()));
                return drop_land_cover_beyond_limits(std::move(cover), report);
            });
            scene.trees = timed(report, "trees", [&] {
                return place_trees(osm, projection, scene, job.params.trees, job.params.seed, report);
            });
            scene.trees.shrink_to_fit();
        },
        [&](ParseReport& report) {
            scene.crossings = timed(report, "crossings", [&] { return place_crossings(osm, projection, scene, report); });
        },
    });
    if (!job.params.blocks.enabled) {
        trim_heap();  // and the last stages' working sets
        if (encoder) {
            finish_buildings_in_slices();
        } else {
            roofs_and_colours(report);
        }
    }
    set_bounds_and_ground(scene, freed_buildings_box);
    return scene;
}

}  // namespace

Scene parse_osm_to_scene(const ParseJob& job, ParseReport& report) {
    tbb::task_arena arena(job.threads > 0 ? job.threads : tbb::task_arena::automatic);
    Scene scene = arena.execute([&] { return run_pipeline(job, report, nullptr); });
    // The OSM data and the stages' working sets are freed now, in small pieces all over the heap
    // (one arena, see main.cpp): hand their pages back before the scene is encoded, so encoding
    // adds to what the scene holds, not to the stages' peak (Kaiserslautern: 92 MB -> 72 MB).
    trim_heap();
    return scene;
}

void parse_osm_to_file(const ParseJob& job, ParseReport& report, const std::string& path) {
    tbb::task_arena arena(job.threads > 0 ? job.threads : tbb::task_arena::automatic);
    std::unique_ptr<SceneEncoder> encoder;
    Scene scene = arena.execute([&] { return run_pipeline(job, report, &encoder); });
    release(scene.buildings);  // encoded, and read for the bounds
    trim_heap();
    // Each part is freed once encoded, and its pages handed back before the encoder takes
    // more: the encoded scene grows as the in-memory one shrinks.
    encoder->finish_releasing(scene, trim_heap);
    check_scene_loads(encoder->data(), encoder->size(), path);  // never a file its loader refuses
    write_file_atomically(path, encoder->data(), encoder->size());  // no copy of the bytes
}

}  // namespace citygen
