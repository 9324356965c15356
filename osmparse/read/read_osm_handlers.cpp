#include "osmparse/read/read_osm_handlers.h"

#include <algorithm>
#include <cstring>

#include "osmparse/read/land_cover_tags.h"
#include "osmparse/read/read_osm.h"

namespace citygen {

bool is_building_tags(const osmium::TagList& tags) {
    return tags.has_key("building") || tags.has_key("building:part");
}

OsmTags copy_tags(const osmium::TagList& tags) {
    OsmTags out;
    out.entries.reserve(tags.size());  // exactly: a growing vector holds up to twice its tags
    for (const osmium::Tag& t : tags) out.entries.emplace_back(t.key(), t.value());
    return out;
}

namespace {

LatLon to_latlon(osmium::Location l) { return {l.lat(), l.lon()}; }

// A building's tags but its address (addr:*), which no stage reads: in a city extract the
// address is most of what the buildings are tagged with (docs/bench/2026-11-parse.md), and the
// building areas are held until the roofs and colours are done.
OsmTags copy_building_tags(const osmium::TagList& tags) {
    auto kept = [](const osmium::Tag& t) { return std::strncmp(t.key(), "addr:", 5) != 0; };
    OsmTags out;
    out.entries.reserve(static_cast<size_t>(std::count_if(tags.begin(), tags.end(), kept)));
    for (const osmium::Tag& t : tags)
        if (kept(t)) out.entries.emplace_back(t.key(), t.value());
    return out;
}

// data.min and data.max cover every location of street lamps, highways, tree rows and building
// areas. Coastlines reach far beyond a clipped extract: they do not extend the data's bounds
// (the sea is clipped to the extract, see assemble_sea.h).
void extend_bounds(OsmData& data, const LatLon& l) {
    data.min.lat = std::min(data.min.lat, l.lat);
    data.min.lon = std::min(data.min.lon, l.lon);
    data.max.lat = std::max(data.max.lat, l.lat);
    data.max.lon = std::max(data.max.lon, l.lon);
}

// Cuts the way into runs of nodes whose locations are known and appends the runs of at least
// two nodes to `out`; returns how many nodes had a location. With `data_bounds` every located
// node extends the data's bounds.
size_t keep_runs(const osmium::Way& way, std::vector<OsmWay>& out, OsmData* data_bounds) {
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
        if (data_bounds) extend_bounds(*data_bounds, run.locations.back());
    }
    if (!run.nodes.empty()) flush(false);
    return located;
}

// The node, when it has a location (else counted as dropped under `kind`).
bool keep_node(const osmium::Node& node, std::vector<OsmNode>& out, ParseReport& report, ReportKind kind) {
    if (!node.location().valid()) {
        report.dropped(kind, ReportReason::InvalidLocation);
        return false;
    }
    out.push_back({node.id(), to_latlon(node.location()), copy_tags(node.tags())});
    return true;
}

// The rings libosmium assembled: each outer ring with its inner rings.
std::vector<OsmPolygon> area_polygons(const osmium::Area& area) {
    std::vector<OsmPolygon> polygons;
    for (const osmium::OuterRing& outer : area.outer_rings()) {
        OsmPolygon polygon;
        for (const osmium::NodeRef& ref : outer) polygon.outer.push_back(to_latlon(ref.location()));
        for (const osmium::InnerRing& inner : area.inner_rings(outer)) {
            polygon.inners.emplace_back();
            for (const osmium::NodeRef& ref : inner) polygon.inners.back().push_back(to_latlon(ref.location()));
        }
        polygons.push_back(std::move(polygon));
    }
    return polygons;
}

OsmRef area_ref(const osmium::Area& area) {
    return {area.from_way() ? OsmType::Way : OsmType::Relation, area.orig_id()};
}

}  // namespace

void StreetLampHandler::node(const osmium::Node& node) {
    if (!node.tags().has_tag("highway", "street_lamp")) return;
    report_.read(ReportKind::TaggedStreetLamps);
    if (keep_node(node, data_.street_lamps, report_, ReportKind::TaggedStreetLamps))
        extend_bounds(data_, data_.street_lamps.back().location);
}

void TreeHandler::node(const osmium::Node& node) {
    if (!node.tags().has_tag("natural", "tree")) return;
    report_.read(ReportKind::MappedTrees);
    keep_node(node, data_.trees, report_, ReportKind::MappedTrees);
}

void TreeHandler::way(const osmium::Way& way) {
    if (!way.tags().has_tag("natural", "tree_row")) return;
    report_.read(ReportKind::TreeRows);
    if (keep_runs(way, data_.tree_rows, &data_) == 0) report_.dropped(ReportKind::TreeRows, ReportReason::NodesMissing);
}

void RoadMarkHandler::node(const osmium::Node& node) {
    if (!node.tags().has_tag("highway", "crossing") && !node.tags().has_tag("highway", "traffic_signals")) return;
    report_.read(ReportKind::RoadMarkNodes);
    // Not counted as dropped when unlocated: the row counts what the file maps.
    if (node.location().valid())
        data_.road_marks.push_back({node.id(), to_latlon(node.location()), copy_tags(node.tags())});
}

void HighwayHandler::way(const osmium::Way& way) {
    if (!way.tags().has_key("highway")) return;
    report_.read(ReportKind::HighwayWays);
    const size_t before = data_.highways.size();
    const bool clipped = keep_runs(way, data_.highways, &data_) != way.nodes().size();
    if (data_.highways.size() == before) report_.dropped(ReportKind::HighwayWays, ReportReason::NodesMissing);
    else if (clipped) report_.note(ReportKind::HighwayWays, ReportReason::ClippedAtEdge);
}

void CoastlineHandler::way(const osmium::Way& way) {
    if (!way.tags().has_tag("natural", "coastline")) return;
    report_.read(ReportKind::CoastlineWays);
    if (keep_runs(way, data_.coastlines, nullptr) == 0)
        report_.dropped(ReportKind::CoastlineWays, ReportReason::NodesMissing);
}

void RailwayHandler::way(const osmium::Way& way) {
    const char* railway = way.tags().get_value_by_key("railway");
    if (!railway) return;
    if (std::strcmp(railway, "rail") && std::strcmp(railway, "tram") && std::strcmp(railway, "light_rail") &&
        std::strcmp(railway, "subway"))
        return;
    report_.read(ReportKind::RailwayWays);
    if (keep_runs(way, data_.railways, nullptr) == 0)
        report_.dropped(ReportKind::RailwayWays, ReportReason::NodesMissing);
}

void RetainingWallHandler::way(const osmium::Way& way) {
    if (!way.tags().has_tag("barrier", "retaining_wall")) return;
    const size_t before = data_.retaining_walls.size();
    keep_runs(way, data_.retaining_walls, nullptr);
    // A run keeps only the tags build_retaining_walls reads.
    for (size_t k = before; k < data_.retaining_walls.size(); ++k) {
        OsmWay& run = data_.retaining_walls[k];
        auto& entries = run.tags.entries;
        entries.erase(std::remove_if(entries.begin(), entries.end(),
                                     [](const auto& kv) { return kv.first != "height" && kv.first != "material"; }),
                      entries.end());
    }
    // A way without two present nodes in a row leaves no run: an empty one stands for it, so
    // build_retaining_walls counts it as dropped.
    if (data_.retaining_walls.size() == before) {
        OsmWay missing;
        missing.id = way.id();
        data_.retaining_walls.push_back(std::move(missing));
    }
}

void PierLineHandler::way(const osmium::Way& way) {
    const char* man_made = way.tags()["man_made"];
    if (!man_made || (std::strcmp(man_made, "pier") != 0 && std::strcmp(man_made, "breakwater") != 0)) return;
    if (way.is_closed() && !way.tags().has_tag("area", "no")) return;  // an area: LandCoverHandler's
    const size_t before = data_.pier_lines.size();
    keep_runs(way, data_.pier_lines, nullptr);
    for (size_t k = before; k < data_.pier_lines.size(); ++k) {
        auto& entries = data_.pier_lines[k].tags.entries;
        entries.erase(std::remove_if(entries.begin(), entries.end(), [](const auto& kv) { return kv.first != "width"; }),
                      entries.end());
    }
}

void BuildingAreaHandler::way(const osmium::Way& way) {
    if (!is_building_tags(way.tags())) return;
    report_.read(ReportKind::BuildingWays);
    if (way.nodes().empty() || !way.is_closed()) {  // is_closed asserts on a way of no nodes
        report_.dropped(ReportKind::BuildingWays, ReportReason::NotClosed);
        return;
    }
    std::vector<LatLon> outline;
    outline.reserve(way.nodes().size());
    for (const osmium::NodeRef& ref : way.nodes()) {
        if (!ref.location().valid()) {
            report_.dropped(ReportKind::BuildingWays, ReportReason::NodesMissing);
            return;
        }
        outline.push_back(to_latlon(ref.location()));
    }
    way_outlines_[way.id()] = std::move(outline);
}

void BuildingAreaHandler::relation(const osmium::Relation& relation) {
    if (is_building_tags(relation.tags()) && relation.tags().has_tag("type", "multipolygon"))
        report_.read(ReportKind::BuildingRelations);
}

void BuildingAreaHandler::area(const osmium::Area& area) {
    if (!is_building_tags(area.tags())) return;
    OsmArea out;
    out.ref = area_ref(area);
    out.tags = copy_building_tags(area.tags());
    out.polygons = area_polygons(area);
    if (area.from_way()) {
        auto outline = way_outlines_.find(area.orig_id());
        if (outline != way_outlines_.end()) {
            if (out.polygons.empty()) {
                out.polygons.push_back({std::move(outline->second), {}});
                report_.note(ReportKind::BuildingAreas, ReportReason::OutlinePassedForRepair);
            }
            way_outlines_.erase(outline);
        }
    }
    if (out.polygons.empty()) {
        report_.dropped(ReportKind::BuildingAreas, ReportReason::CouldNotAssemble);
        return;
    }
    for (const OsmPolygon& p : out.polygons)
        for (const LatLon& l : p.outer) extend_bounds(data_, l);
    data_.building_areas.push_back(std::move(out));
}

void LandCoverHandler::area(const osmium::Area& area) {
    if (is_building_tags(area.tags())) return;  // a building, whatever else it is
    OsmArea out;
    out.tags = copy_tags(area.tags());
    if (!land_cover_class(out.tags)) return;
    out.ref = area_ref(area);
    report_.read(ReportKind::LandCoverAreas);
    out.polygons = area_polygons(area);
    if (out.polygons.empty()) {
        report_.dropped(ReportKind::LandCoverAreas, ReportReason::CouldNotAssemble);
        return;
    }
    data_.land_cover_areas.push_back(std::move(out));
}

}  // namespace citygen
