// osmparse from top to bottom: the stage list in parse_stages is the one place the order is
// declared, with what each stage reads and writes; run_stages (run_stages.h) runs it, frees each
// part after its last reader and times each stage.
#include "osmparse/pipeline.h"

#include <algorithm>
#include <memory>
#include <optional>

#include <tbb/task_arena.h>

#include "common/rng.h"
#include "common/scene_io.h"
#include "osmparse/buildings/build_buildings.h"
#include "osmparse/buildings/building_colours.h"
#include "osmparse/buildings/building_tags.h"
#include "osmparse/buildings/infer_heights.h"
#include "common/projection.h"
#include "osmparse/map/assemble_sea.h"
#include "osmparse/map/build_land_cover.h"
#include "osmparse/map/build_retaining_walls.h"
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
#include "osmparse/run_stages.h"
#include "osmparse/terrain/bridges_from_layers.h"
#include "osmparse/terrain/build_terrain.h"
#include "osmparse/terrain/fit_terrain.h"
#include "osmparse/terrain/retaining_wall_steps.h"
#include "osmparse/tiles/keep_inside_box.h"

namespace citygen {

namespace {

// Frees a vector whose last reader is done, so later stages can reuse its memory.
template <typename T>
void release(std::vector<T>& v) {
    std::vector<T>().swap(v);
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
    // Only when given: a scene parsed without them keeps its bytes.
    if (job.origin) h.options.emplace_back("origin", to_text(*job.origin));
    if (job.keep_inside) h.options.emplace_back("keep-inside", to_text(*job.keep_inside));
    std::sort(h.options.begin(), h.options.end());
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

// The parts of the parse, each named in the stage list by the string in its comment.
struct ParseState {
    ParseState(const ParseJob& job, bool to_file) : job(job), to_file(to_file) {}
    const ParseJob& job;
    const ParseParams& params() const { return job.params; }
    const bool to_file;  // parse_osm_to_file: the buildings are encoded as soon as they are final

    OsmData osm;                          // "osm" (but the two below)
    //                                       "osm building areas": osm.building_areas
    //                                       "osm ways": osm.highways and osm.railways
    std::optional<Projection> projection;  // "projection"
    Scene scene;  // "header", "buildings", "roads", "joints", "sidewalks", "paths", "lamps", ..., "terrain"
    std::optional<BuildingTagIndex> building_tags;  // "building tags": what roofs and colours read
    RoofEvidence roof_evidence;  // "roof evidence": the map's tagged roofs, which untagged ones follow
    RegionStatistics statistics;  // "region statistics" (gather_region_statistics)
    size_t map_buildings = 0;  // the map's buildings come first; the empty blocks' after them
    RoadGraph road_graph;      // "road graph"
    std::unordered_map<int64_t, int> way_layers;  // "way layers": the nonzero layers of highways and railways
    NarrowedRoads narrowed;    // "narrowed roads"
    RoadSurface surface;       // "road surface"
    PathSurface paths;         // "path surface"

    // "building slices": the buildings once every other stage is done with them, finished (roofs
    // and colours) and encoded a slice at a time; `has_roofs`: the empty blocks' buildings.
    struct BuildingSlice {
        std::vector<Building> buildings;
        bool has_roofs = false;
    };
    std::vector<BuildingSlice> slices;
    size_t slice = 0;  // the one the per-slice stages work on

    std::unique_ptr<SceneEncoder> encoder;  // "encoded scene" (parse_osm_to_file)
    Box2 encoded_box;                       // the bounds of the buildings encoded and freed
};

void read(ParseState& s, ParseReport& report) {
    s.osm = read_osm(s.job.input, s.job.quiet, report);
    if (s.job.hide_height_tags > 0) hide_height_tags(s.osm, s.job.hide_height_tags, s.params().seed);
    if (s.job.hide_roof_tags > 0) hide_roof_tags(s.osm, s.job.hide_roof_tags, s.params().seed);
    s.projection.emplace(s.job.origin ? Projection(s.job.origin->lat, s.job.origin->lon) : projection_for(s.osm));
    s.scene.header = make_header(s.job, *s.projection);
}

void infer_building_heights(ParseState& s, ParseReport& report) {
    const BuildingParams& params = s.params().buildings;
    const std::optional<RegionStatistics>& region = s.job.region_statistics;
    infer_heights(s.scene.buildings, land_use_areas(s.osm, *s.projection, report), params, report,
                  homes_by_use(s.osm), region ? &region->heights : nullptr);
    // The building areas' rings are in the footprints now; the roofs and colours read only
    // some of their tags: those are kept, the areas freed.
    s.building_tags.emplace(std::move(s.osm.building_areas));
    s.map_buildings = s.scene.buildings.size();
    s.roof_evidence = region ? region->roofs : roof_evidence(s.scene.buildings, *s.building_tags);
}

// A tile's part of the region's statistics: the buildings anchored in its core box, each counted
// by exactly one tile (as keep_inside_box keeps it).
void gather_statistics(ParseState& s, ParseReport&) {
    std::function<bool(const Building&)> counted;
    if (s.job.keep_inside)
        counted = [&s](const Building& b) { return box_holds(*s.job.keep_inside, *s.projection, ring_anchor(b.outer)); };
    ParseReport again;  // the heights' stage reported the land use already
    s.statistics.heights = height_evidence(s.scene.buildings, land_use_areas(s.osm, *s.projection, again),
                                           s.params().buildings, homes_by_use(s.osm), counted);
    s.statistics.roofs = roof_evidence(s.scene.buildings, *s.building_tags, counted);
}

void lay_out_road_lanes(ParseState& s, ParseReport& report) {
    lay_out_lanes(s.surface.roads, s.osm, report);
    // The highways' last reader is the paths, after the sidewalks: only their ways wait.
    keep_path_ways(s.osm.highways);
}

void lay_out_sidewalks(ParseState& s, ParseReport& report) {
    s.scene.sidewalks = build_sidewalks(s.narrowed.graph, s.surface, s.scene.buildings, s.params().sidewalks,
                                        s.params().roads.miter_limit, report);
    s.scene.roads = std::move(s.surface.roads);
    s.scene.joints = std::move(s.surface.joints);
}

void lay_out_paths(ParseState& s, ParseReport& report) {
    const bool with_terrain = !s.params().terrain.dem_files.empty();
    s.paths = build_paths(s.osm, *s.projection, s.params().roads, with_terrain, report);
}

void put_paths_in_scene(ParseState& s, ParseReport& report) {
    s.scene.sidewalks = drop_doubled_sidewalks(std::move(s.scene.sidewalks), s.paths.paths, report);
    s.scene.paths = std::move(s.paths.paths);
    s.scene.path_joints = std::move(s.paths.joints);
}

void add_empty_blocks(ParseState& s, ParseReport& report) {
    const ParseParams& p = s.params();
    std::vector<Building> generated = fill_empty_blocks(s.scene, p.buildings, p.blocks, p.sidewalks.width, s.roof_evidence, report);
    s.scene.buildings.insert(s.scene.buildings.end(), generated.begin(), generated.end());
}

void lay_out_land_cover(ParseState& s, ParseReport& report) {
    const bool with_piers = !s.params().terrain.dem_files.empty();
    std::vector<LandCover> cover = build_land_cover(s.osm, *s.projection, s.params().buildings, with_piers, report);
    const Box2 sea_box = s.job.keep_inside ? tile_sea_box(*s.job.keep_inside, s.osm, *s.projection)
                                           : extract_box(s.osm, *s.projection);
    std::vector<LandCover> sea = assemble_sea(s.osm, *s.projection, sea_box, s.scene.buildings, report);
    cover.insert(cover.end(), std::make_move_iterator(sea.begin()), std::make_move_iterator(sea.end()));
    s.scene.land_cover = drop_land_cover_beyond_limits(std::move(cover), report);
}

// Roofs and colours change only the heights, roofs and colours of the buildings, and no other
// stage reads those: they run last, so the roof faces (megabytes on a city) are not held while
// another stage's working set is. For the file, the buildings are then finished and encoded a
// slice at a time, each slice freed before the next is built: the roof faces and footprints are
// never held all at once, and the encoded scene grows as they are freed. Each building's roof and
// colours are its own: the same roofs, colours, report and bytes as all at once.
void slice_buildings(ParseState& s, ParseReport&) {
    std::vector<Building>& all = s.scene.buildings;
    if (s.to_file) {
        // Reserved before the roofs exist: the bound of the rest alone is ~2x the whole
        // encoded scene on the real extracts; a short reserve costs only a copy as it grows.
        s.encoder = std::make_unique<SceneEncoder>(s.scene.header, 2 * encoded_size_bound(s.scene));
    }
    // A slice of the file's buildings: build_roofs still runs on every thread.
    const size_t slice = s.to_file ? 1024 : all.size();
    auto add_slices = [&](size_t begin, size_t end, bool has_roofs) {
        for (; begin < end; begin += std::max<size_t>(slice, 1)) {
            const auto first = all.begin() + static_cast<std::ptrdiff_t>(begin);
            const auto last = all.begin() + static_cast<std::ptrdiff_t>(std::min(end, begin + slice));
            s.slices.push_back({{std::make_move_iterator(first), std::make_move_iterator(last)}, has_roofs});
        }
    };
    add_slices(0, s.map_buildings, false);
    add_slices(s.map_buildings, all.size(), true);  // the empty blocks' buildings
    release(all);  // each slice is freed when encoded, not all of them with the last
}

void build_slice_roofs(ParseState& s, ParseReport& report) {
    ParseState::BuildingSlice& slice = s.slices[s.slice];
    if (!slice.has_roofs)
        build_roofs(slice.buildings, *s.building_tags, s.params().buildings, report, &s.roof_evidence);
}

void choose_slice_colours(ParseState& s, ParseReport& report) {
    ParseState::BuildingSlice& slice = s.slices[s.slice];
    if (!slice.has_roofs)
        choose_colours_and_materials(slice.buildings, *s.building_tags, s.params().buildings, report);
}

// Nothing reads the buildings after this but the scene's bounds: encoded, they are freed once
// their extent is taken, and the encoded scene grows into their memory.
void encode_slice(ParseState& s, ParseReport&) {
    std::vector<Building>& buildings = s.slices[s.slice].buildings;
    extend_by_footprints(s.encoded_box, buildings);
    for (const Building& b : buildings) s.encoder->add_building(b);
    release(buildings);
}

void gather_buildings(ParseState& s, ParseReport&) {
    for (ParseState::BuildingSlice& slice : s.slices)
        s.scene.buildings.insert(s.scene.buildings.end(), std::make_move_iterator(slice.buildings.begin()),
                                 std::make_move_iterator(slice.buildings.end()));
}

// The stages in the order they run; stages side by side when none reads what another writes.
std::vector<Stage> parse_stages(ParseState& s) {
    const ParseParams& p = s.params();
    Scene& scene = s.scene;
    auto run = [&s](void (*f)(ParseState&, ParseReport&)) { return [&s, f](ParseReport& r) { f(s, r); }; };
    return {
        {"read", {}, {"osm", "osm building areas", "osm ways", "projection", "header"}, run(read)},
        {"buildings", {"osm building areas", "projection"}, {"buildings"},
         [&](ParseReport& r) { scene.buildings = build_buildings(s.osm, *s.projection, p.buildings, r); }},
        {"building heights", {"osm", "osm building areas", "projection", "buildings"},
         {"buildings", "building tags", "roof evidence", "osm building areas"}, run(infer_building_heights)},
        {"road graph", {"osm ways", "projection"}, {"road graph"},
         [&](ParseReport& r) {
             s.road_graph = build_road_graph(s.osm, *s.projection, p.roads, r, !p.terrain.dem_files.empty());
         }},
        {"way layers", {"osm ways"}, {"way layers"}, [&](ParseReport&) { s.way_layers = way_layers(s.osm); },
         !p.terrain.dem_files.empty()},
        // Beside the roads against the buildings; the sea's flood check sees the map's buildings.
        {"land cover", {"osm", "projection", "buildings"}, {"land cover"}, run(lay_out_land_cover)},
        {"roads vs buildings", {"road graph", "buildings"}, {"narrowed roads"},
         [&](ParseReport& r) { s.narrowed = narrow_roads(std::move(s.road_graph), scene.buildings, p.roads, r); }},
        {"road polygons", {"narrowed roads"}, {"road surface"},
         [&](ParseReport& r) { s.surface = build_road_polygons(s.narrowed.graph, std::move(s.narrowed.layout), r); }},
        {"lanes", {"road surface", "osm", "osm ways"}, {"road surface", "osm ways"}, run(lay_out_road_lanes)},
        {"sidewalks", {"narrowed roads", "road surface", "buildings"}, {"sidewalks", "roads", "joints"},
         run(lay_out_sidewalks)},
        // Beside the sidewalks: the paths read only the ways.
        {"paths and rails", {"osm", "osm ways", "projection"}, {"path surface"}, run(lay_out_paths)},
        {"paths off sidewalks", {"path surface", "sidewalks"}, {"paths", "sidewalks"}, run(put_paths_in_scene)},
        {"empty blocks", {"buildings", "roads", "joints", "sidewalks", "paths", "roof evidence"}, {"buildings"},
         run(add_empty_blocks), p.blocks.enabled},
        {"street lamps", {"osm", "projection", "buildings", "roads", "joints", "sidewalks"}, {"lamps"},
         [&](ParseReport& r) {
             scene.lamps = place_lamps(s.osm, *s.projection, scene, p.lamps, p.seed, r);
             scene.lamps.shrink_to_fit();  // counted as placed (grown by doubling), then kept to the end
         }},
        // --dem: ways above others by their layer get decks, as bridges do.
        {"layered bridges", {"roads", "paths", "way layers", "land cover"}, {"roads", "paths"},
         [&](ParseReport& r) { mark_layered_bridges(scene.roads, scene.paths, s.way_layers, scene.land_cover, r); },
         !p.terrain.dem_files.empty()},
        // Only with a field, as the piers: on the flat ground the scene stays what it was.
        {"retaining walls", {"osm", "projection"}, {"retaining walls"},
         [&](ParseReport& r) { scene.retaining_walls = build_retaining_walls(s.osm, *s.projection, r); },
         !p.terrain.dem_files.empty()},
        {"trees", {"osm", "projection", "buildings", "roads", "joints", "paths", "land cover"}, {"trees"},
         [&](ParseReport& r) {
             scene.trees = place_trees(s.osm, *s.projection, scene, p.trees, p.seed, r);
             scene.trees.shrink_to_fit();
         }},
        {"crossings", {"osm", "projection", "roads", "joints", "sidewalks", "paths"}, {"crossings"},
         [&](ParseReport& r) { scene.crossings = place_crossings(s.osm, *s.projection, scene, r); }},
        // --keep-inside: after the last stage that looks at the neighbours, before the buildings go.
        {"keep inside", {"projection", "buildings", "roads", "joints", "sidewalks", "lamps", "land cover", "trees", "paths", "crossings"},
         {"buildings", "roads", "joints", "sidewalks", "lamps", "land cover", "trees", "paths", "crossings"},
         [&](ParseReport& r) { s.map_buildings = keep_inside_box(scene, *s.projection, *s.job.keep_inside, r, s.map_buildings); },
         s.job.keep_inside.has_value()},
        {"slice buildings", {"buildings", "header"}, {"building slices", "buildings", "encoded scene"},
         run(slice_buildings)},
        {"roofs", {"building slices", "building tags", "roof evidence"}, {"building slices"}, run(build_slice_roofs),
         true, true},
        {"colours", {"building slices", "building tags"}, {"building slices"}, run(choose_slice_colours), true,
         true},
        {"encode buildings", {"building slices"}, {"encoded scene"}, run(encode_slice), s.to_file, true},
        {"gather buildings", {"building slices"}, {"buildings"}, run(gather_buildings), !s.to_file},
        {"bounds", {"buildings", "roads", "joints", "sidewalks", "lamps", "land cover", "trees", "paths", "crossings"},
         {"header", "ground"},
         [&](ParseReport&) { set_bounds_and_ground(scene, s.encoded_box); }},
        // --dem: over the bounds (so after them), with the sea, where a void is at the coast.
        {"terrain", {"header", "projection", "land cover"}, {"terrain"},
         [&](ParseReport& r) { scene.terrain = build_terrain(scene.header, *s.projection, scene.land_cover, p.terrain, r); },
         !p.terrain.dem_files.empty()},
        {"roads into terrain", {"terrain", "roads", "paths"}, {"terrain"},
         [&](ParseReport& r) { fit_terrain_to_ways(scene.terrain, scene.roads, scene.paths, {p.sidewalks.width}, r); },
         !p.terrain.dem_files.empty()},
        {"walls into terrain", {"terrain", "roads", "paths", "retaining walls"}, {"terrain"},
         [&](ParseReport& r) {
             step_terrain_at_walls(scene.terrain, scene.retaining_walls,
                                   way_corridor_nodes(scene.terrain, scene.roads, scene.paths, {p.sidewalks.width}), r);
         },
         !p.terrain.dem_files.empty()},
        {"water into terrain", {"terrain", "land cover", "paths"}, {"terrain"},
         [&](ParseReport& r) {
             level_still_water(scene.terrain, scene.land_cover, r);
             raise_piers(scene.terrain, scene.land_cover, r);
             note_steps(scene, r);  // on the finished field
         },
         !p.terrain.dem_files.empty()},
    };
}

// How each intermediate part is freed after its last reader (the scene's parts are the result).
StageHooks parse_hooks(ParseState& s) {
    StageHooks hooks;
    hooks.free = {
        {"osm", [&s] { s.osm = OsmData(); }},
        {"osm building areas", [&s] { release(s.osm.building_areas); }},
        {"osm ways", [&s] { release(s.osm.highways); release(s.osm.railways); }},
        {"building tags", [&s] { s.building_tags.reset(); }},
        {"road graph", [&s] { s.road_graph = RoadGraph(); }},
        {"way layers", [&s] { s.way_layers = {}; }},
        {"narrowed roads", [&s] { s.narrowed = NarrowedRoads(); }},
        {"road surface", [&s] { s.surface = RoadSurface(); }},
        {"path surface", [&s] { s.paths = PathSurface(); }},
        {"building slices", [&s] { release(s.slices); }},
    };
    hooks.slice_count = [&s] { return s.slices.size(); };
    hooks.select_slice = [&s](size_t i) { s.slice = i; };
    return hooks;
}

void run_pipeline(ParseState& state, const std::vector<Stage>& stages, ParseReport& report) {
    tbb::task_arena arena(state.job.threads > 0 ? state.job.threads : tbb::task_arena::automatic);
    arena.execute([&] { run_stages(stages, parse_hooks(state), report); });
}

}  // namespace

Scene parse_osm_to_scene(const ParseJob& job, ParseReport& report) {
    ParseState state(job, false);
    run_pipeline(state, parse_stages(state), report);
    return std::move(state.scene);
}

RegionStatistics gather_region_statistics(const ParseJob& job, ParseReport& report) {
    ParseState state(job, false);
    std::vector<Stage> stages = parse_stages(state);
    const auto heights = std::find_if(stages.begin(), stages.end(), [](const Stage& st) { return st.name == "building heights"; });
    stages.erase(heights + 1, stages.end());
    stages.push_back({"region statistics", {"osm", "projection", "buildings", "building tags"}, {"region statistics"},
                      [&state](ParseReport& r) { gather_statistics(state, r); }});
    run_pipeline(state, stages, report);
    return std::move(state.statistics);
}

void parse_osm_to_file(const ParseJob& job, ParseReport& report, const std::string& path) {
    ParseState state(job, true);
    run_pipeline(state, parse_stages(state), report);
    // Each part is freed once encoded: the encoded scene grows as the in-memory one shrinks.
    state.encoder->finish_releasing(state.scene);
    const uint8_t* bytes = state.encoder->data();
    const size_t size = state.encoder->size();
    // Never a file its loader refuses: decoded while the bytes go to disk.
    write_file_atomically(path, bytes, size, [&] { check_scene_loads(bytes, size, path); });
}

}  // namespace citygen
