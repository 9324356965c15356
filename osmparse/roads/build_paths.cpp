#include "osmparse/roads/build_paths.h"

#include <algorithm>
#include <cstring>
#include <iterator>
#include <map>
#include <unordered_map>

#include "osmparse/core/osm_units.h"
#include "osmparse/polygons/polygon_overlap.h"
#include "osmparse/roads/build_road_graph.h"
#include "osmparse/roads/build_road_polygons.h"
#include "osmparse/roads/build_sidewalks.h"
#include "osmparse/roads/road_layout.h"

namespace citygen {

namespace {

struct ClassInfo {
    const char* tag;  // the highway=* or railway=* value
    PathClass cls;
    double width;
};
const ClassInfo kTable[] = {
    {"footway", PathClass::Footway, 2.0},   {"path", PathClass::Path, 1.5},
    {"cycleway", PathClass::Cycleway, 2.0}, {"pedestrian", PathClass::Pedestrian, 5.0},
    {"steps", PathClass::Steps, 2.0},       {"track", PathClass::Track, 3.0},
    {"bridleway", PathClass::Bridleway, 2.0}, {"rail", PathClass::Rail, 3.0},
    {"tram", PathClass::Tram, 2.6},         {"light_rail", PathClass::LightRail, 3.0},
    {"subway", PathClass::Subway, 3.0},
};

// The graph builder reads highway=*: every path way gets a highway value naming its class.
std::string graph_key(PathClass c) { return std::string("citygen-path-") + to_string(c); }

// What a path edge takes from its way besides its class and width.
struct PathWayFlags {
    bool sidewalk = false;
    bool bridge = false;
};

// Lays out one network (paths, or rails) and appends its edges and joints to `out`.
void lay_out(std::vector<OsmWay> ways, const Projection& projection, const RoadParams& roads,
             const std::unordered_map<int64_t, std::pair<PathClass, double>>& info,
             const std::unordered_map<int64_t, PathWayFlags>& flags, PathSurface& out, ParseReport& report) {
    if (ways.empty()) return;
    OsmData data;
    data.highways = std::move(ways);
    RoadParams params = roads;
    params.classes.clear();
    for (const ClassInfo& c : kTable) params.classes.push_back(graph_key(c.cls));
    ParseReport scratch;  // the graph builder counts under "road ..." rows: not ours
    RoadGraph graph = build_road_graph(data, projection, params, scratch);
    std::vector<SideWidths> widths;
    for (RoadGraphEdge& e : graph.edges) {
        e.width = info.at(e.way_id).second;
        widths.push_back({0.5 * e.width, 0.5 * e.width});
    }
    RoadLayout layout = layout_road_polygons(graph, widths, roads.miter_limit);
    // Exactly (the paths are the scene's, kept to the end of the parse).
    out.paths.reserve(out.paths.size() + quad_count(layout));
    out.joints.reserve(out.joints.size() + joint_count(layout));
    std::vector<int> path_of_edge(graph.edges.size(), -1);
    for (size_t e = 0; e < graph.edges.size(); ++e) {
        report.read(ReportKind::PathEdges);
        if (layout.absorbed[e] || layout.quads[e].empty()) {
            report.dropped(ReportKind::PathEdges, layout.absorbed[e] ? ReportReason::AbsorbedIntoMergedJunction
                                                                     : ReportReason::TooShortForJunctions);
            continue;
        }
        const RoadGraphEdge& g = graph.edges[e];
        PathEdge p;
        p.osm = {OsmType::Way, g.way_id};
        p.from_node = g.from_node;
        p.to_node = g.to_node;
        p.centreline = {g.from, g.to};
        p.quad = std::move(layout.quads[e]);  // moved, as the joints below: nothing reads the layout after
        p.width = g.width;
        p.path_class = info.at(g.way_id).first;
        if (auto f = flags.find(g.way_id); f != flags.end()) {
            p.sidewalk = f->second.sidewalk;
            p.bridge = f->second.bridge;
        }
        path_of_edge[e] = static_cast<int>(out.paths.size());
        out.paths.push_back(std::move(p));
    }
    for (NodeLayout& node : layout.nodes) {
        if (node.kind != JoinKind::Joint || node.joint.empty()) continue;
        Joint j;
        j.osm = {OsmType::Node, node.node};
        j.polygon = std::move(node.joint);
        const int index = static_cast<int>(out.joints.size());
        for (const NodeLayout::End& end : node.ends) {
            const int path = path_of_edge[end.edge];
            if (path < 0) continue;
            j.edges.push_back(static_cast<uint32_t>(path));
            (end.at_from ? out.paths[path].from_joint : out.paths[path].to_joint) = index;
        }
        out.joints.push_back(std::move(j));
    }
}

}  // namespace

ReportKind path_class_row(PathClass c) {
    using K = ReportKind;
    static const ReportKind kRows[kPathClassCount] = {  // in PathClass order
        K::PathFootway, K::PathPath, K::PathCycleway, K::PathPedestrian, K::PathSteps,   K::PathTrack,
        K::PathBridleway, K::PathRail, K::PathTram,   K::PathLightRail,  K::PathSubway,
    };
    return kRows[static_cast<int>(c)];
}

std::optional<PathClass> path_class_of(const OsmTags& tags) {
    const char* highway = tags.get("highway");
    const char* railway = tags.get("railway");
    for (const ClassInfo& c : kTable) {
        const char* value = is_rail(c.cls) ? railway : highway;
        if (value && !std::strcmp(value, c.tag)) return c.cls;
    }
    return std::nullopt;
}

double path_width(const OsmTags& tags, PathClass c, ParseReport* report) {
    if (const char* w = tags.get("width")) {
        const std::optional<double> width = parse_osm_length(w);
        if (width && *width >= 1 && *width <= 20) return *width;
        if (report) report->note(ReportKind::PathEdges, ReportReason::WidthTagUnusable);
    }
    for (const ClassInfo& info : kTable)
        if (info.cls == c) return info.width;
    return 2;
}

// The tags build_paths reads (path_class_of, take, path_width).
constexpr const char* kPathTagsRead[] = {"highway", "railway", "tunnel", "area",   "indoor",
                                         "width",   "footway", "bridge", "covered"};

void keep_path_ways(std::vector<OsmWay>& highways) {
    std::vector<OsmWay> kept;
    kept.reserve(static_cast<size_t>(
        std::count_if(highways.begin(), highways.end(), [](const OsmWay& w) { return path_class_of(w.tags).has_value(); })));
    for (OsmWay& way : highways) {
        if (!path_class_of(way.tags)) continue;
        auto& entries = way.tags.entries;
        entries.erase(std::remove_if(entries.begin(), entries.end(),
                                     [](const auto& kv) {
                                         return std::none_of(std::begin(kPathTagsRead), std::end(kPathTagsRead),
                                                             [&](const char* k) { return kv.first == k; });
                                     }),
                      entries.end());
        entries.shrink_to_fit();
        kept.push_back(std::move(way));
    }
    highways = std::move(kept);  // the other ways (and the old list) freed
}

PathSurface build_paths(const OsmData& osm, const Projection& projection, const RoadParams& roads,
                        bool with_terrain, ParseReport& report) {
    std::vector<OsmWay> paths, rails;
    std::unordered_map<int64_t, std::pair<PathClass, double>> info;
    std::unordered_map<int64_t, PathWayFlags> flags;
    auto take = [&](const OsmWay& way, std::vector<OsmWay>& into) {
        const std::optional<PathClass> c = path_class_of(way.tags);
        if (!c) return;
        const char* tunnel = way.tags.get("tunnel");
        if ((tunnel && std::strcmp(tunnel, "no") != 0) || way.tags.has("area", "yes") ||
            way.tags.has("indoor", "yes")) {
            report.dropped(ReportKind::PathWays, tunnel ? ReportReason::Tunnel : ReportReason::AreaOrIndoor);
            return;
        }
        report.read(ReportKind::PathWays);
        if (with_terrain && is_covered(way.tags)) report.note(ReportKind::PathWays, ReportReason::Covered);
        if (!info.count(way.id)) info[way.id] = {*c, path_width(way.tags, *c, &report)};
        flags[way.id] = {way.tags.has("footway", "sidewalk"), with_terrain && is_bridge(way.tags)};
        OsmWay copy = way;
        copy.tags.entries = {{"highway", graph_key(*c)}};
        into.push_back(std::move(copy));
    };
    for (const OsmWay& way : osm.highways) take(way, paths);
    for (const OsmWay& way : osm.railways) take(way, rails);
    PathSurface out;
    lay_out(std::move(paths), projection, roads, info, flags, out, report);
    lay_out(std::move(rails), projection, roads, info, flags, out, report);
    report.kept(ReportKind::PathEdges, static_cast<int64_t>(out.paths.size()));
    for (const PathEdge& p : out.paths) report.kept(path_class_row(p.path_class));
    report.kept(ReportKind::PathJoints, static_cast<int64_t>(out.joints.size()));
    return out;
}

std::vector<Sidewalk> drop_doubled_sidewalks(std::vector<Sidewalk> sidewalks, const std::vector<PathEdge>& paths,
                                             ParseReport& report) {
    // Mapped sidewalks are drawn where people walk, often a few metres off our strip: each
    // reaches kSidewalkReach further to both sides for this test.
    constexpr double kSidewalkReach = 2.5;
    std::vector<Building> mapped;
    for (const PathEdge& p : paths) {
        if (!p.sidewalk || p.centreline.size() < 2) continue;
        const Vec2 a = p.centreline.front(), b = p.centreline.back();
        const Vec2 n = perp_left(normalize(b - a)) * (0.5 * p.width + kSidewalkReach);
        mapped.push_back({p.osm, Ring{a - n, b - n, b + n, a + n}, {}, 0, 0, 0, {}, {}, false});
    }
    if (mapped.empty()) return sidewalks;
    const BuildingIndex index(mapped, 25);
    std::vector<Sidewalk> kept;
    kept.reserve(sidewalks.size());
    for (Sidewalk& s : sidewalks) {
        const double area = std::fabs(signed_area(s.polygon));
        double covered = 0;
        index.for_each_near(bounds_of(s.polygon), [&](uint32_t i) { covered += clipped_area(s.polygon, mapped[i].outer); });
        if (area > 0 && covered > area / 3) {
            const ReportKind kind =
                s.kind == SidewalkKind::Strip ? ReportKind::SidewalkStrips : ReportKind::SidewalkCorners;
            report.dropped(kind, ReportReason::ReplacedByMappedSidewalk);
            report.kept(kind, -1);  // build_sidewalks counted it as kept
            continue;
        }
        kept.push_back(std::move(s));
    }
    return kept;
}

}  // namespace citygen
