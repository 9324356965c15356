// osmparse: OpenStreetMap data in, citygen scene out. Also --info and --diff on scenes.
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

#include <CLI/CLI.hpp>

#include "common/error.h"
#include "common/output_target.h"
#include "common/scene_info.h"
#include "common/scene_io.h"
#include "osmparse/heap/huge_page_heap.h"
#include "osmparse/output/diff_scenes.h"
#include "osmparse/output/write_geojson.h"
#include "osmparse/pipeline.h"
#include "osmparse/terrain/read_dem.h"

using namespace citygen;

namespace {

int run_info(const std::string& path) {
    print_scene_info(load_scene(path), path, stdout);
    return 0;
}

int run_diff(const std::vector<std::string>& files, double tolerance) {
    const Scene a = load_scene(files[0]);
    const Scene b = load_scene(files[1]);
    const std::vector<SceneChange> changes = diff_scenes(a, b, tolerance);
    for (const SceneChange& c : changes)
        std::printf("%-8s %s%s%s\n", c.what.c_str(), c.object.c_str(), c.detail.empty() ? "" : ": ",
                    c.detail.c_str());
    std::printf("%zu difference%s beyond %.3f m\n", changes.size(), changes.size() == 1 ? "" : "s",
                tolerance);
    return changes.empty() ? 0 : 1;
}

std::vector<std::string> split_list(const std::string& text) {
    std::vector<std::string> out;
    std::stringstream in(text);
    for (std::string item; std::getline(in, item, ',');)
        if (!item.empty()) out.push_back(item);
    return out;
}

// The command line's values that are not ParseJob's own.
struct Options {
    std::string output, info_file, geojson;
    std::vector<std::string> diff_files;
    double tolerance = 0.01;
    std::string ignore_types, road_classes, trees = "all";
    CLI::Option* dem_resolution = nullptr;  // given or not: 0 is an error, not the default
    std::string origin, keep_inside;        // the farm's tiles (docs/farm.md)
    std::vector<std::string> region_statistics;  // one file a tile: their sum
    std::string write_region_statistics;
};

void add_file_options(CLI::App& app, ParseJob& job, Options& o) {
    app.add_option("input", job.input, "OSM input: .osm, .osm.gz, .osm.bz2 or .osm.pbf");
    app.add_option("-o,--output", o.output, "scene file to write");
    app.add_option("--info", o.info_file, "print a summary of a scene file and exit");
    app.add_option("--diff", o.diff_files, "compare two scene files; exit 0 only if they match")
        ->expected(2);
    app.add_option("--tolerance", o.tolerance, "distance in metres below which --diff ignores moves")
        ->check(CLI::Range(0.0, 1e6))->capture_default_str();
    app.add_option("--geojson", o.geojson, "also write the scene as GeoJSON in WGS84");
}

void add_building_options(CLI::App& app, ParseParams& p, Options& o) {
    app.add_option("--building-min-h", p.buildings.random_min_height,
                   "lowest random height (m) for buildings with no height tags")
        ->check(CLI::Range(0.0, 1000.0))->capture_default_str();
    app.add_option("--building-max-h", p.buildings.random_max_height,
                   "highest random height (m) for buildings with no height tags")
        ->check(CLI::Range(0.0, 1000.0))->capture_default_str();
    app.add_option("--simplify-angle", p.buildings.simplify_angle_deg,
                   "merge footprint edges whose direction changes by less than this (degrees)")
        ->check(CLI::Range(0.0, 45.0))->capture_default_str();
    app.add_option("--ignore-building-types", o.ignore_types,
                   "comma-separated building=* values to skip (default: roof,carport,ruins,...)");
    app.add_flag("--fill-empty-blocks", p.blocks.enabled,
                 "generate buildings in built-up road-graph blocks the map left empty (marked generated)");
}

void add_road_and_map_options(CLI::App& app, ParseParams& p, Options& o) {
    app.add_option("--road-classes", o.road_classes,
                   "comma-separated highway=* values that are carriageways (default: motorway ... service)");
    app.add_option("--road-merge-angle", p.roads.merge_angle_deg,
                   "merge consecutive road edges turning less than this at degree-2 nodes (degrees)")
        ->check(CLI::Range(0.0, 90.0))->capture_default_str();
    app.add_option("--road-min-width", p.roads.min_width,
                   "roads narrowed below this width (m) near buildings are dropped")
        ->check(CLI::Range(0.0, 100.0))->capture_default_str();
    app.add_option("--lamp-spacing", p.lamps.spacing, "distance between generated street lamps (m)")
        ->check(CLI::Range(1.0, 10000.0))->capture_default_str();
    app.add_option("--trees", o.trees, "which trees: none, mapped (natural=tree nodes and tree rows) or all (+ forests)")
        ->check(CLI::IsMember({"none", "mapped", "all"}))->capture_default_str();
    app.add_option("--forest-tree-spacing", p.trees.forest_spacing, "least distance between trees scattered in forests (m)")
        ->check(CLI::Range(1.0, 1000.0))->capture_default_str();
    app.add_option("--dem", p.terrain.dem_files,
                   "elevation raster for the terrain (SRTM .hgt or .hgt.zip, GeoTIFF, VRT; any CRS); repeat for "
                   "several, the first given wins where they overlap")
        ->allow_extra_args(false)->take_all();
    o.dem_resolution = app.add_option("--dem-resolution", p.terrain.resolution,
                                      "metres between the terrain's nodes (default: the finest DEM's own, at least 1)");
}

void add_run_options(CLI::App& app, ParseJob& job) {
    app.add_option("--seed", job.params.seed, "seed for every random choice")->capture_default_str();
    app.add_option("--hide-height-tags", job.hide_height_tags,
                   "benchmark aid: ignore height, building:levels, min_height, roof:height, ... on this "
                   "fraction of buildings (seeded; 1 = all)")
        ->check(CLI::Range(0.0, 1.0));
    app.add_option("--hide-roof-tags", job.hide_roof_tags,
                   "benchmark aid: ignore roof:shape on this fraction of buildings (seeded; 1 = all)")
        ->check(CLI::Range(0.0, 1.0));
    app.add_option("--threads", job.threads,
                   "at most this many threads for the stages after reading (0: every core); the scene "
                   "is the same whatever the number")
        ->check(CLI::Range(0, 1024))->capture_default_str();
    app.add_flag("-q,--quiet", job.quiet, "no progress and no report on stderr");
}

void add_tile_options(CLI::App& app, Options& o) {
    app.add_option("--origin", o.origin,
                   "LAT,LON: the projection's origin instead of the data's centre (tiles of one region share it)");
    app.add_option("--keep-inside", o.keep_inside,
                   "MINLAT,MINLON,MAXLAT,MAXLON: keep only objects anchored in this half-open box (a tile's core "
                   "without its overlap; needs --origin)");
    app.add_option("--write-region-statistics", o.write_region_statistics,
                   "FILE: write what the height and roof rules read of the buildings anchored in --keep-inside "
                   "(all without it) and stop, with no scene; the tiles' files concatenated are the region's");
    app.add_option("--region-statistics", o.region_statistics,
                   "FILE: the height and roof rules read these statistics (a region's, from "
                   "--write-region-statistics) instead of the extract's own; repeat it for several files, summed")
        ->expected(1)
        ->take_all();
}

void set_tile_options(ParseJob& job, const Options& o) {
    if (!o.origin.empty()) {
        job.origin = parse_lat_lon(o.origin, "--origin");
        job.params.trees.local_scatter = true;  // the same trees in a tile as in the whole region
    }
    if (!o.keep_inside.empty()) {
        if (!job.origin) throw Error("--keep-inside needs --origin (the tiles' shared frame)");
        job.keep_inside = parse_lat_lon_box(o.keep_inside, "--keep-inside");
    }
    if (!o.region_statistics.empty()) job.region_statistics = read_region_statistics(o.region_statistics);
}

// Checks the options against each other and the outputs before the (possibly long) parse, then
// parses and writes.
int run_parse(ParseJob& job, const Options& o) {
    ParseParams& p = job.params;
    const bool statistics_only = !o.write_region_statistics.empty();
    if (statistics_only && (!o.output.empty() || !o.geojson.empty()))
        throw Error("--write-region-statistics writes no scene: leave out -o and --geojson");
    const std::string& output = statistics_only ? o.write_region_statistics : o.output;
    if (job.input.empty() || output.empty()) throw Error("need an input file and -o OUTPUT.scene (see --help)");
    std::vector<std::string> inputs = o.region_statistics;
    inputs.push_back(job.input);
    check_output_target(output, inputs);
    if (!o.geojson.empty()) {
        check_output_target(o.geojson, {job.input, o.output});
        if (o.geojson == o.output) throw Error("--geojson and -o name the same file");
    }
    if (p.buildings.random_min_height > p.buildings.random_max_height)
        throw Error("--building-min-h is larger than --building-max-h");
    if (!o.ignore_types.empty()) p.buildings.ignore_types = split_list(o.ignore_types);
    if (!o.road_classes.empty()) p.roads.classes = split_list(o.road_classes);
    if (o.dem_resolution->count() > 0) {
        if (p.terrain.dem_files.empty()) throw Error("--dem-resolution needs --dem");
        if (!(p.terrain.resolution > 0) || !std::isfinite(p.terrain.resolution))
            throw Error("--dem-resolution must be a positive number of metres");
    }
    check_dem_files(p.terrain.dem_files);  // before the parse: a bad file fails at once
    set_tile_options(job, o);
    p.buildings.seed = p.seed;
    p.trees.mode = o.trees == "none" ? TreeMode::None : o.trees == "mapped" ? TreeMode::Mapped : TreeMode::All;

    ParseReport report;
    if (statistics_only) {
        write_region_statistics(output, gather_region_statistics(job, report));
    } else if (o.geojson.empty()) {
        parse_osm_to_file(job, report, o.output);  // the lower peak memory
    } else {
        const Scene scene = parse_osm_to_scene(job, report);
        const std::vector<uint8_t> bytes = encode_scene(scene);
        write_file_atomically(o.output, bytes.data(), bytes.size(),  // never a file its loader refuses
                              [&] { check_scene_loads(bytes.data(), bytes.size(), o.output); });
        write_geojson(scene, o.geojson);
    }
    if (!job.quiet) report.print(stderr);
    return 0;
}

}  // namespace

int main(int argc, char** argv) {
    use_huge_pages_for_the_heap();
    CLI::App app{"osmparse: turn OpenStreetMap data into a citygen scene"};
    app.set_version_flag("--version", std::string("citygen osmparse ") + CITYGEN_VERSION);
    ParseJob job;
    Options o;
    add_file_options(app, job, o);
    add_run_options(app, job);
    add_building_options(app, job.params, o);
    add_road_and_map_options(app, job.params, o);
    add_tile_options(app, o);
    try {
        app.parse(argc, argv);
    } catch (const CLI::Success& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::fprintf(stderr, "osmparse: %s (see --help)\n", e.what());
        return 2;
    }

    try {
        if (!o.info_file.empty()) return run_info(o.info_file);
        if (!o.diff_files.empty()) return run_diff(o.diff_files, o.tolerance);
        return run_parse(job, o);
    } catch (const Error& e) {
        std::fprintf(stderr, "osmparse: %s\n", e.what());
        return 1;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "osmparse: unexpected error: %s\n", e.what());
        return 1;
    }
}
