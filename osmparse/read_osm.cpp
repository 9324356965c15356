#include "read_osm.h"

#include <sys/stat.h>

#include <cerrno>
#include <cstring>

#include <osmium/area/assembler.hpp>
#include <osmium/area/multipolygon_manager.hpp>
#include <osmium/handler/node_locations_for_ways.hpp>
#include <osmium/index/map/sparse_mem_array.hpp>
#include <osmium/io/any_input.hpp>
#include <osmium/relations/relations_manager.hpp>
#include <osmium/tags/tags_filter.hpp>
#include <osmium/visitor.hpp>

#include "build_land_cover.h"
#include "error.h"
#include "progress.h"
#include "read_osm_handlers.h"

namespace citygen {

namespace {

using LocationIndex =
    osmium::index::map::SparseMemArray<osmium::unsigned_object_id_type, osmium::Location>;
using LocationHandler = osmium::handler::NodeLocationsForWays<LocationIndex, LocationIndex>;

void check_input_file(const std::string& path) {
    struct stat st {};
    if (::stat(path.c_str(), &st) != 0)
        throw Error(path + ": cannot open input (" + std::strerror(errno) + ")");
    if (S_ISDIR(st.st_mode)) throw Error(path + ": is a directory, not an OSM file");
    if (st.st_size == 0) throw Error(path + ": empty file, not OSM data");
}

// The header's box (<bounds> or the PBF header box), when the file gives one.
void keep_extract_bounds(const osmium::io::Header& header, OsmData& data) {
    const osmium::Box box = header.box();
    if (box.valid() && box.bottom_left().lat() < box.top_right().lat() &&
        box.bottom_left().lon() < box.top_right().lon()) {
        data.has_extract_bounds = true;
        data.extract_min = {box.bottom_left().lat(), box.bottom_left().lon()};
        data.extract_max = {box.top_right().lat(), box.top_right().lon()};
    }
}

}  // namespace

OsmData read_osm(const std::string& path, bool quiet, ParseReport& report) {
    check_input_file(path);
    OsmData data;
    try {
        const osmium::io::File file(path);

        osmium::TagsFilter area_filter{false};
        area_filter.add_rule(true, osmium::TagMatcher{"building"});
        area_filter.add_rule(true, osmium::TagMatcher{"building:part"});
        // Land cover goes through the same assembler (a superset of the keys that
        // land_cover_class reads; LandCoverHandler sorts the areas out).
        for (const char* key : land_cover_keys()) area_filter.add_rule(true, osmium::TagMatcher{key});
        osmium::area::Assembler::config_type assembler_config;
        osmium::area::MultipolygonManager<osmium::area::Assembler> multipolygons{assembler_config, area_filter};

        LocationIndex positive, negative;
        LocationHandler locations{positive, negative};
        locations.ignore_errors();  // clipped extracts: missing nodes are normal, counted by the handlers
        BuildingAreaHandler buildings{data, report};
        CoastlineHandler coastlines{data, report};
        TreeHandler trees{data, report};
        RoadMarkHandler road_marks{data, report};
        StreetLampHandler street_lamps{data, report};
        RailwayHandler railways{data, report};
        HighwayHandler highways{data, report};
        LandCoverHandler land_cover{data, report};

        // One walk over the file. Multipolygon assembly must know the relations before it sees
        // their member ways, and relations come last in an OSM file: so the walk also hands the
        // relations to the multipolygon manager (its first pass) and copies the ways aside, with
        // their node locations filled in; the manager's second pass then runs over that copy
        // alone. Ways are a small part of a file (nodes are most of it), so this costs less
        // memory than keeping the file and less time than reading it twice.
        osmium::memory::Buffer ways{1024 * 1024, osmium::memory::Buffer::auto_grow::yes};
        {
            osmium::io::Reader reader{file, osmium::osm_entity_bits::object};
            keep_extract_bounds(reader.header(), data);
            Progress progress("reading", reader.file_size(), quiet);
            uint64_t last_offset = 0;
            while (osmium::memory::Buffer buffer = reader.read()) {
                // The order of the handlers is the order of the report's rows.
                osmium::apply(buffer, locations, multipolygons, buildings, coastlines, trees, road_marks,
                              street_lamps, railways, highways);
                for (const osmium::Way& way : buffer.select<osmium::Way>()) {
                    ways.add_item(way);
                    ways.commit();
                }
                const uint64_t offset = reader.offset();
                progress.advance(offset - last_offset);
                last_offset = offset;
            }
            reader.close();
        }
        multipolygons.prepare_for_lookup();
        // Areas from closed ways and from the multipolygons whose members all arrived.
        osmium::apply(ways, multipolygons.handler([&](osmium::memory::Buffer&& areas) {
                          osmium::apply(areas, buildings, land_cover);
                      }));

        int64_t incomplete = 0, incomplete_cover = 0;
        multipolygons.for_each_incomplete_relation([&](const osmium::relations::RelationHandle& handle) {
            if (is_building_tags(handle->tags())) ++incomplete;
            else if (land_cover_class(copy_tags(handle->tags()))) ++incomplete_cover;
        });
        if (incomplete) report.dropped(kBuildingRelations, kMembersMissing, incomplete);
        if (incomplete_cover) report.dropped(kLandCoverAreas, kRelationMembersMissing, incomplete_cover);
        report.read(kBuildingAreas, static_cast<int64_t>(data.building_areas.size()));
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(path + ": cannot read OSM data: " + e.what());
    }
    return data;
}

}  // namespace citygen
