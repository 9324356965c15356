#include "osmparse/read/read_osm.h"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <memory>
#include <vector>

#include <osmium/area/assembler.hpp>
#include <osmium/area/multipolygon_manager.hpp>
#include <osmium/handler/node_locations_for_ways.hpp>
#include <osmium/index/map/sparse_mem_array.hpp>
#include <osmium/io/any_input.hpp>
#include <osmium/relations/relations_manager.hpp>
#include <osmium/tags/tags_filter.hpp>
#include <osmium/visitor.hpp>
#include <tbb/parallel_for.h>

#include "common/error.h"
#include "common/progress.h"
#include "osmparse/read/land_cover_tags.h"
#include "osmparse/read/read_osm_handlers.h"

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

// Where one area of the second pass comes from, in the order libosmium's multipolygon manager
// makes them: a closed way (assembled later, `way`) or a relation (assembled at once into
// `relation_areas`). Then the areas themselves: [begin, end) of `buffer`.
struct AreaJob {
    const osmium::Way* way = nullptr;
    const osmium::memory::Buffer* buffer = nullptr;
    size_t begin = 0, end = 0;
};

// The assembler the multipolygon manager runs (its template parameter). A closed way's area
// depends on that way alone: it is only noted here, in the manager's order, and assembled by
// assemble_way_areas in parallel; a relation's area is assembled at once, when its last member
// arrives, as the manager would. Their areas reach the handlers in the manager's order.
class DeferringAssembler {
public:
    struct config_type {
        osmium::area::Assembler::config_type assembler;
        std::vector<AreaJob>* jobs = nullptr;
        osmium::memory::Buffer* relation_areas = nullptr;
    };
    explicit DeferringAssembler(const config_type& config) : config_(config) {}

    bool operator()(const osmium::Way& way, osmium::memory::Buffer& /*manager's buffer*/) {
        config_.jobs->push_back({&way});
        return true;
    }
    bool operator()(const osmium::Relation& relation, const std::vector<const osmium::Way*>& members,
                    osmium::memory::Buffer& /*manager's buffer*/) {
        osmium::memory::Buffer& out = *config_.relation_areas;
        const size_t begin = out.committed();
        osmium::area::Assembler assembler{config_.assembler};
        bool okay = false;
        try {
            okay = assembler(relation, members, out);
        } catch (...) {
            out.rollback();
            throw;
        }
        stats_ += assembler.stats();
        config_.jobs->push_back({nullptr, &out, begin, out.committed()});
        return okay;
    }
    const osmium::area::area_stats& stats() const noexcept { return stats_; }

private:
    const config_type& config_;
    osmium::area::area_stats stats_;
};

// The closed ways' areas, in parallel blocks of jobs, each block into a buffer of its own.
std::vector<std::unique_ptr<osmium::memory::Buffer>> assemble_way_areas(
    std::vector<AreaJob>& jobs, const osmium::area::Assembler::config_type& config) {
    constexpr size_t kBlock = 256;
    std::vector<std::unique_ptr<osmium::memory::Buffer>> buffers((jobs.size() + kBlock - 1) / kBlock);
    tbb::parallel_for(size_t{0}, buffers.size(), [&](size_t block) {
        buffers[block] = std::make_unique<osmium::memory::Buffer>(64 * 1024, osmium::memory::Buffer::auto_grow::yes);
        osmium::memory::Buffer& out = *buffers[block];
        for (size_t j = block * kBlock; j < std::min(jobs.size(), (block + 1) * kBlock); ++j) {
            AreaJob& job = jobs[j];
            if (!job.way) continue;
            job.buffer = &out;
            job.begin = out.committed();
            try {
                osmium::area::Assembler assembler{config};
                assembler(*job.way, out);
            } catch (const osmium::invalid_location&) {  // skipped, as the manager does
                out.rollback();
            }
            job.end = out.committed();
        }
    });
    return buffers;
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

// The areas the multipolygon assembler builds: buildings, their parts and land cover (a superset
// of the keys that land_cover_class reads; LandCoverHandler sorts the areas out).
osmium::TagsFilter area_tags_filter() {
    osmium::TagsFilter filter{false};
    filter.add_rule(true, osmium::TagMatcher{"building"});
    filter.add_rule(true, osmium::TagMatcher{"building:part"});
    for (const char* key : land_cover_keys()) filter.add_rule(true, osmium::TagMatcher{key});
    return filter;
}

// Multipolygons whose members the extract cut off: counted as dropped.
void count_incomplete_relations(osmium::area::MultipolygonManager<DeferringAssembler>& multipolygons,
                                ParseReport& report) {
    int64_t incomplete = 0, incomplete_cover = 0;
    multipolygons.for_each_incomplete_relation([&](const osmium::relations::RelationHandle& handle) {
        if (is_building_tags(handle->tags())) ++incomplete;
        else if (land_cover_class(copy_tags(handle->tags()))) ++incomplete_cover;
    });
    if (incomplete) report.dropped(ReportKind::BuildingRelations, ReportReason::MembersMissing, incomplete);
    if (incomplete_cover)
        report.dropped(ReportKind::LandCoverAreas, ReportReason::RelationMembersMissing, incomplete_cover);
}

}  // namespace

OsmData read_osm(const std::string& path, bool quiet, ParseReport& report) {
    check_input_file(path);
    OsmData data;
    try {
        const osmium::io::File file(path);

        const osmium::TagsFilter area_filter = area_tags_filter();
        std::vector<AreaJob> area_jobs;
        osmium::memory::Buffer relation_areas{64 * 1024, osmium::memory::Buffer::auto_grow::yes};
        const DeferringAssembler::config_type assembler_config{{}, &area_jobs, &relation_areas};
        osmium::area::MultipolygonManager<DeferringAssembler> multipolygons{assembler_config, area_filter};

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
        RetainingWallHandler retaining_walls{data, report};
        PierLineHandler pier_lines{data, report};
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
                              street_lamps, railways, highways, retaining_walls, pier_lines);
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
        // Areas from closed ways and from the multipolygons whose members all arrived: the
        // manager's second pass orders them, the closed ways' are assembled in parallel.
        osmium::apply(ways, multipolygons.handler());
        const auto way_areas = assemble_way_areas(area_jobs, assembler_config.assembler);
        for (const AreaJob& job : area_jobs) {
            if (job.begin == job.end) continue;
            for (const osmium::Area& area : osmium::memory::ItemIteratorRange<const osmium::Area>{
                     job.buffer->data() + job.begin, job.buffer->data() + job.end}) {
                buildings.area(area);
                land_cover.area(area);
            }
        }

        count_incomplete_relations(multipolygons, report);
        report.read(ReportKind::BuildingAreas, static_cast<int64_t>(data.building_areas.size()));
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw Error(path + ": cannot read OSM data: " + e.what());
    }
    return data;
}

}  // namespace citygen
