#include "read_osm.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>
#include <unordered_map>

#include <osmium/area/assembler.hpp>
#include <osmium/area/multipolygon_manager.hpp>
#include <osmium/handler.hpp>
#include <osmium/handler/node_locations_for_ways.hpp>
#include <osmium/index/map/sparse_mem_array.hpp>
#include <osmium/io/any_input.hpp>
#include <osmium/relations/relations_manager.hpp>
#include <osmium/tags/tags_filter.hpp>
#include <osmium/visitor.hpp>

#include "build_land_cover.h"
#include "error.h"
#include "progress.h"

namespace citygen {

namespace {

using LocationIndex =
    osmium::index::map::SparseMemArray<osmium::unsigned_object_id_type, osmium::Location>;
using LocationHandler = osmium::handler::NodeLocationsForWays<LocationIndex, LocationIndex>;

bool is_building_tags(const osmium::TagList& tags) {
    return tags.has_key("building") || tags.has_key("building:part");
}

OsmTags copy_tags(const osmium::TagList& tags) {
    OsmTags out;
    for (const osmium::Tag& t : tags) out.entries.emplace_back(t.key(), t.value());
    return out;
}

LatLon to_latlon(osmium::Location l) { return {l.lat(), l.lon()}; }

// Keeps what later stages need. Called after the location handler has filled in the
// node locations of each way.
class Collector : public osmium::handler::Handler {
public:
    Collector(OsmData& data, ParseReport& report) : data_(data), report_(report) {}

    void node(const osmium::Node& node) {
        if (node.tags().has_tag("natural", "tree")) {
            report_.read("mapped trees");
            if (!node.location().valid()) report_.dropped("mapped trees", "invalid location");
            else data_.trees.push_back({node.id(), to_latlon(node.location()), copy_tags(node.tags())});
        }
        if (node.tags().has_tag("highway", "crossing") || node.tags().has_tag("highway", "traffic_signals")) {
            report_.read("crossing and signal nodes");
            if (node.location().valid())
                data_.road_marks.push_back({node.id(), to_latlon(node.location()), copy_tags(node.tags())});
        }
        if (!node.tags().has_tag("highway", "street_lamp")) return;
        report_.read("tagged street lamps");
        if (!node.location().valid()) {
            report_.dropped("tagged street lamps", "invalid location");
            return;
        }
        extend(node.location());
        data_.street_lamps.push_back({node.id(), to_latlon(node.location()), copy_tags(node.tags())});
    }

    void way(const osmium::Way& way) {
        if (is_building_tags(way.tags()) && way.is_closed()) keep_building_way_ring(way);
        // Coastlines reach far beyond a clipped extract: they do not extend the data's bounds
        // (the sea is clipped to the extract, see assemble_sea.h).
        if (way.tags().has_tag("natural", "coastline")) {
            report_.read("coastline ways");
            if (keep_runs(way, data_.coastlines, false) == 0) report_.dropped("coastline ways", "nodes missing from extract");
        }
        if (way.tags().has_tag("natural", "tree_row")) {
            report_.read("tree rows");
            if (keep_runs(way, data_.tree_rows, true) == 0) report_.dropped("tree rows", "nodes missing from extract");
        }
        if (const char* railway = way.tags().get_value_by_key("railway")) {
            if (!std::strcmp(railway, "rail") || !std::strcmp(railway, "tram") || !std::strcmp(railway, "light_rail") ||
                !std::strcmp(railway, "subway")) {
                report_.read("railway ways");
                if (keep_runs(way, data_.railways, false) == 0) report_.dropped("railway ways", "nodes missing from extract");
            }
        }
        if (!way.tags().has_key("highway")) return;
        report_.read("highway ways");
        const int before = static_cast<int>(data_.highways.size());
        const bool clipped = keep_runs(way, data_.highways, true) != way.nodes().size();
        const int runs_kept = static_cast<int>(data_.highways.size()) - before;
        if (runs_kept == 0) report_.dropped("highway ways", "nodes missing from extract");
        else if (clipped) report_.note("highway ways", "clipped at extract edge");
    }

    // Cuts the way into runs of nodes whose locations are known and appends the runs of at
    // least two nodes to `out`; returns how many nodes had a location.
    size_t keep_runs(const osmium::Way& way, std::vector<OsmWay>& out, bool extend_bounds) {
        size_t located = 0;
        OsmWay run;
        bool missing_before = false;  // a node of the way before the current run is missing
        auto flush = [&](bool cut_after) {
            run.cut_after = cut_after;
            if (run.nodes.size() >= 2) out.push_back(run);
            run.nodes.clear();
            run.locations.clear();
        };
        for (const osmium::NodeRef& ref : way.nodes()) {
            if (!ref.location().valid()) {
                if (!run.nodes.empty()) flush(true);
                missing_before = true;
                continue;
            }
            ++located;
            if (run.nodes.empty()) {
                run.id = way.id();
                run.tags = copy_tags(way.tags());
                run.cut_before = missing_before;
            }
            run.nodes.push_back(ref.ref());
            run.locations.push_back(to_latlon(ref.location()));
            if (extend_bounds) extend(ref.location());
        }
        if (!run.nodes.empty()) flush(false);
        return located;
    }

    void area(const osmium::Area& area) {
        const bool building = is_building_tags(area.tags());
        if (!building) {
            keep_land_cover(area);
            return;
        }
        OsmArea out;
        out.ref = {area.from_way() ? OsmType::Way : OsmType::Relation, area.orig_id()};
        out.tags = copy_tags(area.tags());
        for (const osmium::OuterRing& outer : area.outer_rings()) {
            OsmPolygon polygon;
            for (const osmium::NodeRef& ref : outer) polygon.outer.push_back(to_latlon(ref.location()));
            for (const osmium::InnerRing& inner : area.inner_rings(outer)) {
                polygon.inners.emplace_back();
                for (const osmium::NodeRef& ref : inner)
                    polygon.inners.back().push_back(to_latlon(ref.location()));
            }
            out.polygons.push_back(std::move(polygon));
        }
        if (area.from_way()) {
            // libosmium refuses self-intersecting rings (it yields an empty area); hand
            // the raw outline to the footprint clean-up instead, which can repair it.
            auto raw = building_way_rings_.find(area.orig_id());
            if (out.polygons.empty() && raw != building_way_rings_.end()) {
                out.polygons.push_back({std::move(raw->second), {}});
                report_.note("building areas", "invalid outline passed on for repair");
            }
            if (raw != building_way_rings_.end()) building_way_rings_.erase(raw);
        }
        if (out.polygons.empty()) {
            report_.dropped("building areas", "invalid multipolygon (could not assemble)");
            return;
        }
        for (const OsmPolygon& p : out.polygons)
            for (const LatLon& l : p.outer) extend(osmium::Location(l.lon, l.lat));
        data_.building_areas.push_back(std::move(out));
    }

    // An area with a land cover class (build_land_cover.h); others that the filter let
    // through (e.g. a closed highway=pedestrian way without area=yes) are ignored.
    void keep_land_cover(const osmium::Area& area) {
        OsmArea out;
        out.tags = copy_tags(area.tags());
        if (!land_cover_class(out.tags)) return;
        out.ref = {area.from_way() ? OsmType::Way : OsmType::Relation, area.orig_id()};
        report_.read("land cover areas");
        for (const osmium::OuterRing& outer : area.outer_rings()) {
            OsmPolygon polygon;
            for (const osmium::NodeRef& ref : outer) polygon.outer.push_back(to_latlon(ref.location()));
            for (const osmium::InnerRing& inner : area.inner_rings(outer)) {
                polygon.inners.emplace_back();
                for (const osmium::NodeRef& ref : inner) polygon.inners.back().push_back(to_latlon(ref.location()));
            }
            out.polygons.push_back(std::move(polygon));
        }
        if (out.polygons.empty()) {
            report_.dropped("land cover areas", "invalid multipolygon (could not assemble)");
            return;
        }
        data_.land_cover_areas.push_back(std::move(out));
    }

private:
    // The raw outline of a closed building way, kept until its area arrives.
    void keep_building_way_ring(const osmium::Way& way) {
        std::vector<LatLon> ring;
        ring.reserve(way.nodes().size());
        for (const osmium::NodeRef& ref : way.nodes()) {
            if (!ref.location().valid()) return;  // clipped: counted by BuildingCounter
            ring.push_back(to_latlon(ref.location()));
        }
        building_way_rings_[way.id()] = std::move(ring);
    }
    void extend(osmium::Location l) {
        data_.min.lat = std::min(data_.min.lat, l.lat());
        data_.min.lon = std::min(data_.min.lon, l.lon());
        data_.max.lat = std::max(data_.max.lat, l.lat());
        data_.max.lon = std::max(data_.max.lon, l.lon());
    }
    OsmData& data_;
    ParseReport& report_;
    std::unordered_map<int64_t, std::vector<LatLon>> building_way_rings_;
};

// Counts building ways and relations as they are read, before assembly.
class BuildingCounter : public osmium::handler::Handler {
public:
    explicit BuildingCounter(ParseReport& report) : report_(report) {}
    void way(const osmium::Way& way) {
        if (!is_building_tags(way.tags())) return;
        report_.read("building ways");
        if (!way.is_closed()) {
            report_.dropped("building ways", "not closed");
            return;
        }
        for (const osmium::NodeRef& ref : way.nodes())
            if (!ref.location().valid()) {
                report_.dropped("building ways", "nodes missing from extract");
                return;
            }
    }
    void relation(const osmium::Relation& rel) {
        if (is_building_tags(rel.tags()) && rel.tags().has_tag("type", "multipolygon"))
            report_.read("building relations");
    }

private:
    ParseReport& report_;
};

void check_input_file(const std::string& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0)
        throw Error(path + ": cannot open input (" + std::strerror(errno) + ")");
    if (S_ISDIR(st.st_mode)) throw Error(path + ": is a directory, not an OSM file");
    if (st.st_size == 0) throw Error(path + ": empty file, not OSM data");
}

}  // namespace

OsmData read_osm(const std::string& path, bool quiet, ParseReport& report) {
    check_input_file(path);
    OsmData data;
    try {
        const osmium::io::File file(path);

        osmium::TagsFilter building_filter{false};
        building_filter.add_rule(true, osmium::TagMatcher{"building"});
        building_filter.add_rule(true, osmium::TagMatcher{"building:part"});
        // Land cover goes through the same assembler (a superset of the keys that
        // land_cover_class reads; Collector::area sorts the areas out).
        for (const char* key : land_cover_keys()) building_filter.add_rule(true, osmium::TagMatcher{key});
        osmium::area::Assembler::config_type assembler_config;
        osmium::area::MultipolygonManager<osmium::area::Assembler> multipolygons{assembler_config,
                                                                                building_filter};
        // Multipolygon assembly must know the relations (at the end of the file) before it
        // sees their member ways, so the input is walked twice. XML is parsed once and
        // kept in memory: parsing is the slow part. PBF decodes fast enough to be read
        // twice, which keeps memory low on big cities.
        const bool keep_in_memory = file.format() != osmium::io::file_format::pbf;
        std::vector<osmium::memory::Buffer> buffers;
        auto read_all = [&](osmium::osm_entity_bits::type entities, auto&& use_buffer) {
            osmium::io::Reader reader{file, entities};
            Progress progress("reading", reader.file_size(), quiet);
            uint64_t last_offset = 0;
            while (osmium::memory::Buffer buffer = reader.read()) {
                use_buffer(buffer);
                const uint64_t offset = reader.offset();
                progress.advance(offset - last_offset);
                last_offset = offset;
            }
            reader.close();
        };

        LocationIndex positive, negative;
        LocationHandler locations{positive, negative};
        locations.ignore_errors();  // clipped extracts: missing nodes are normal, counted later
        Collector collector{data, report};
        BuildingCounter building_counter{report};
        // Everything but multipolygon assembly: node locations filled into ways (in the
        // buffer itself, where assembly finds them), street lamps, highways, counts.
        auto collect = [&](osmium::memory::Buffer& buffer) {
            osmium::apply(buffer, locations, building_counter, collector);
        };
        auto assemble_areas = [&](osmium::memory::Buffer& buffer) {
            osmium::apply(buffer, multipolygons.handler([&collector](osmium::memory::Buffer&& areas) {
                              osmium::apply(areas, collector);
                          }));
        };

        // Walk 1: which relations are building multipolygons, and which ways they need.
        // For XML, collecting happens here too, while the parser thread reads on; only
        // assembly waits for walk 2.
        if (keep_in_memory) {
            read_all(osmium::osm_entity_bits::object, [&](osmium::memory::Buffer& buffer) {
                osmium::apply(buffer, multipolygons);
                collect(buffer);
                buffers.push_back(std::move(buffer));
            });
        } else {
            read_all(osmium::osm_entity_bits::relation,
                     [&](osmium::memory::Buffer& buffer) { osmium::apply(buffer, multipolygons); });
        }
        multipolygons.prepare_for_lookup();

        // Walk 2: areas assembled from the ways, now that the relations are known.
        if (keep_in_memory) {
            for (osmium::memory::Buffer& buffer : buffers) assemble_areas(buffer);
            buffers.clear();
        } else {
            read_all(osmium::osm_entity_bits::object, [&](osmium::memory::Buffer& buffer) {
                collect(buffer);
                assemble_areas(buffer);
            });
        }

        int64_t incomplete = 0, incomplete_cover = 0;
        multipolygons.for_each_incomplete_relation([&](const osmium::relations::RelationHandle& handle) {
            if (is_building_tags(handle->tags())) ++incomplete;
            else if (land_cover_class(copy_tags(handle->tags()))) ++incomplete_cover;
        });
        if (incomplete) report.dropped("building relations", "members missing from extract", incomplete);
        if (incomplete_cover) report.dropped("land cover areas", "relation members missing from extract", incomplete_cover);
        {
            osmium::io::Reader header_reader{file, osmium::osm_entity_bits::nothing};
            const osmium::Box box = header_reader.header().box();
            header_reader.close();
            if (box.valid() && box.bottom_left().lat() < box.top_right().lat() &&
                box.bottom_left().lon() < box.top_right().lon()) {
                data.has_extract_bounds = true;
                data.extract_min = to_latlon(box.bottom_left());
                data.extract_max = to_latlon(box.top_right());
            }
        }
        report.read("building areas", static_cast<int64_t>(data.building_areas.size()));
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(path + ": cannot read OSM data: " + e.what());
    }
    return data;
}

}  // namespace citygen
