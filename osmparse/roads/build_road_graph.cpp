#include "osmparse/roads/build_road_graph.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <set>
#include <unordered_map>

#include "common/scene_limits.h"
#include "osmparse/core/osm_units.h"
#include "osmparse/roads/lay_out_lanes.h"

namespace citygen {

namespace {

constexpr double kMinEdgeLength = 0.01;   // metres: shorter pieces are degenerate
constexpr double kMergeDeviation = 0.25;  // metres a skipped node may lie off the merged piece
// Longest straight node-to-node edge kept: half the scene limit on one object's extent, so an
// edge's quad, sidewalks and miters stay well inside it (see scene_limits.h).
constexpr double kMaxRoadEdgeLength = kMaxObjectExtent / 2;
constexpr double kMinTaggedWidth = 1.0;
constexpr double kMaxLanes = 12;

bool is_yes(const char* v) { return v && (!std::strcmp(v, "yes") || !std::strcmp(v, "true") || !std::strcmp(v, "1")); }

struct Piece {
    int64_t a, b;
    Vec2 pa, pb;
};

// A way's pieces, in order along it.
struct WayPieces {
    const OsmWay* way;
    std::vector<Piece> pieces;
};

// Step 1: included ways, as node-to-node pieces; duplicate pieces (overlapping ways) dropped.
std::vector<WayPieces> cut_into_pieces(const OsmData& osm, const Projection& projection, const RoadParams& params,
                                       bool with_terrain, ParseReport& report) {
    std::vector<WayPieces> ways;
    std::set<std::pair<int64_t, int64_t>> seen_pairs;
    for (const OsmWay& way : osm.highways) {
        const std::optional<ReportReason> why = carriageway_exclusion(way.tags, params);
        if (why && (*why == ReportReason::NotACarriagewayClass || *why == ReportReason::NotAHighway)) continue;
        report.read(ReportKind::RoadWays);
        if (why) {
            report.dropped(ReportKind::RoadWays, *why);
            continue;
        }
        WayPieces wp{&way, {}};
        std::vector<Vec2> points;  // each node projected once (projecting is costly)
        points.reserve(way.locations.size());
        for (const LatLon& l : way.locations) points.push_back(projection.to_local(l.lat, l.lon));
        for (size_t i = 0; i + 1 < way.nodes.size(); ++i) {
            const int64_t a = way.nodes[i], b = way.nodes[i + 1];
            if (a == b) continue;  // repeated node: not a piece at all
            const Vec2 pa = points[i], pb = points[i + 1];
            if (length(pb - pa) < kMinEdgeLength) {
                report.dropped(ReportKind::RoadEdges, ReportReason::ZeroLength);
                continue;
            }
            // A mapping mistake (a node moved across the map); later stages' cost grows with it.
            if (length(pb - pa) > kMaxRoadEdgeLength) {
                report.dropped(ReportKind::RoadEdges, ReportReason::Over5Km);
                continue;
            }
            if (std::max({std::fabs(pa.x), std::fabs(pa.y), std::fabs(pb.x), std::fabs(pb.y)}) > kMaxCoordinate) {
                report.dropped(ReportKind::RoadEdges, ReportReason::FarFromOrigin);
                continue;
            }
            if (!seen_pairs.insert({std::min(a, b), std::max(a, b)}).second) {
                report.dropped(ReportKind::RoadEdges, ReportReason::DuplicatePiece);
                continue;
            }
            wp.pieces.push_back({a, b, pa, pb});
        }
        if (wp.pieces.empty()) {
            report.dropped(ReportKind::RoadWays, ReportReason::NoPieceLeft);
            continue;
        }
        if (with_terrain && is_covered(way.tags)) report.note(ReportKind::RoadWays, ReportReason::Covered);
        ways.push_back(std::move(wp));
    }
    report.kept(ReportKind::RoadWays, static_cast<int64_t>(ways.size()));
    return ways;

}

// Step 2: degree of every node: how many piece ends meet there.
std::unordered_map<int64_t, int> node_degrees(const std::vector<WayPieces>& ways) {
    std::unordered_map<int64_t, int> degree;
    for (const WayPieces& wp : ways)
        for (const Piece& p : wp.pieces) {
            ++degree[p.a];
            ++degree[p.b];
        }
    return degree;
}

// What every edge of a way shares: its width, class, lanes and sides.
RoadGraphEdge edge_template(const OsmWay& way, const RoadParams& params, ParseReport& report) {
    const OsmTags& tags = way.tags;
    const std::string highway = tags.get("highway");
    RoadGraphEdge proto;
    proto.way_id = way.id;
    proto.road_class = road_class_of(highway);
    proto.width = road_width(tags, params, &report);
    if (std::optional<double> lanes = parse_osm_count(tags.get("lanes")); lanes && *lanes <= kMaxLanes)
        proto.lanes = static_cast<int>(*lanes);
    proto.oneway = is_oneway(tags);
    proto.bridge = is_bridge(tags);
    const SidewalkSides sides = sidewalk_sides(tags);
    proto.sidewalk_left = sides.left;
    proto.sidewalk_right = sides.right;
    return proto;
}

// Step 3: merge runs of nearly collinear pieces of the same way through degree-2 nodes
// into edges.
RoadGraph merge_collinear_runs(const std::vector<WayPieces>& ways, const std::unordered_map<int64_t, int>& degree,
                               const RoadParams& params, ParseReport& report) {
    const double max_turn = params.merge_angle_deg * kPi / 180;
    auto within_merge = [&](const std::vector<Piece>& run, const Piece& next) {
        const Vec2 start = run.front().pa, end = next.pb;
        if (run.front().a == next.b) return false;  // would close a loop
        const Vec2 chord = end - start;
        const double chord_len = length(chord);
        if (chord_len < kMinEdgeLength || chord_len > kMaxRoadEdgeLength) return false;
        const Vec2 dir = chord * (1.0 / chord_len);
        auto check = [&](const Piece& p) {
            const Vec2 d = normalize(p.pb - p.pa);
            if (std::acos(std::clamp(dot(d, dir), -1.0, 1.0)) >= max_turn) return false;
            return std::fabs(cross(dir, p.pb - start)) <= kMergeDeviation;
        };
        const Vec2 last = normalize(run.back().pb - run.back().pa), nd = normalize(next.pb - next.pa);
        if (std::acos(std::clamp(dot(last, nd), -1.0, 1.0)) >= max_turn) return false;
        for (const Piece& p : run)
            if (!check(p)) return false;
        return check(next);
    };

    RoadGraph graph;
    for (const WayPieces& wp : ways) {
        const RoadGraphEdge proto = edge_template(*wp.way, params, report);

        std::vector<Piece> run;
        auto flush = [&] {
            if (run.empty()) return;
            RoadGraphEdge e = proto;
            e.from_node = run.front().a;
            e.to_node = run.back().b;
            e.from = run.front().pa;
            e.to = run.back().pb;
            graph.edges.push_back(e);
            if (run.size() > 1) report.note(ReportKind::RoadEdges, ReportReason::MergedCollinear, run.size() - 1);
            run.clear();
        };
        for (const Piece& p : wp.pieces) {
            const bool continues = !run.empty() && run.back().b == p.a && degree.at(p.a) == 2;
            if (continues && within_merge(run, p)) {
                run.push_back(p);
                continue;
            }
            flush();
            run.push_back(p);
        }
        flush();
    }
    return graph;
}

}  // namespace

RoadClass road_class_of(const std::string& highway) {
    static const std::map<std::string, RoadClass> table{
        {"motorway", RoadClass::Motorway},         {"motorway_link", RoadClass::Motorway},
        {"trunk", RoadClass::Trunk},               {"trunk_link", RoadClass::Trunk},
        {"primary", RoadClass::Primary},           {"primary_link", RoadClass::Primary},
        {"secondary", RoadClass::Secondary},       {"secondary_link", RoadClass::Secondary},
        {"tertiary", RoadClass::Tertiary},         {"tertiary_link", RoadClass::Tertiary},
        {"unclassified", RoadClass::Unclassified}, {"residential", RoadClass::Residential},
        {"living_street", RoadClass::LivingStreet}, {"service", RoadClass::Service},
    };
    auto it = table.find(highway);
    return it == table.end() ? RoadClass::Other : it->second;
}

double default_road_width(const std::string& highway, bool oneway) {
    // Whole carriageway, kerb to kerb, in metres: typical European urban values. One-way
    // roads (and roundabouts) carry fewer lanes; links and motorway carriageways are
    // one-way anyway. Keep README's table in sync.
    struct Widths {
        double two_way, one_way;
    };
    static const std::map<std::string, Widths> table{
        {"motorway", {11.0, 11.0}},     {"motorway_link", {5.0, 5.0}}, {"trunk", {10.0, 7.0}},
        {"trunk_link", {5.0, 5.0}},     {"primary", {9.0, 6.5}},       {"primary_link", {5.0, 5.0}},
        {"secondary", {8.0, 6.0}},      {"secondary_link", {5.0, 5.0}}, {"tertiary", {7.0, 5.0}},
        {"tertiary_link", {5.0, 5.0}},  {"unclassified", {5.5, 4.0}},  {"residential", {6.0, 4.0}},
        {"living_street", {5.0, 3.5}},  {"service", {3.5, 3.0}},
    };
    auto it = table.find(highway);
    if (it == table.end()) return oneway ? 3.5 : 5.0;
    return oneway ? it->second.one_way : it->second.two_way;
}

bool is_bridge(const OsmTags& tags) { return tags.get("bridge") && !tags.has("bridge", "no"); }

bool is_covered(const OsmTags& tags) { return tags.get("covered") && !tags.has("covered", "no"); }

bool is_oneway(const OsmTags& tags) {
    const char* v = tags.get("oneway");
    if (v) return is_yes(v) || !std::strcmp(v, "-1");
    return tags.has("highway", "motorway") || tags.has("junction", "roundabout") || tags.has("junction", "circular");
}

std::optional<ReportReason> carriageway_exclusion(const OsmTags& tags, const RoadParams& params) {
    const char* highway = tags.get("highway");
    if (!highway) return ReportReason::NotAHighway;
    if (std::find(params.classes.begin(), params.classes.end(), highway) == params.classes.end())
        return ReportReason::NotACarriagewayClass;
    if (tags.has("area", "yes")) return ReportReason::AreaYes;
    const char* tunnel = tags.get("tunnel");
    if (tunnel && std::strcmp(tunnel, "no") != 0) return ReportReason::Tunnel;
    return std::nullopt;
}

double road_width(const OsmTags& tags, const RoadParams& params, ParseReport* report) {
    if (const char* w = tags.get("width")) {
        std::optional<double> width = parse_osm_length(w);
        if (width && *width >= kMinTaggedWidth && *width <= params.max_width) return *width;
        if (report) report->note(ReportKind::RoadEdges, ReportReason::WidthTagUnusable);
    }
    if (const char* l = tags.get("lanes")) {
        std::optional<double> lanes = parse_osm_count(l);
        if (lanes && *lanes >= 1 && *lanes <= kMaxLanes)
            return std::floor(*lanes) * params.lane_width + lane_extras_width(tags);
        if (report) report->note(ReportKind::RoadEdges, ReportReason::LanesTagUnusable);
    }
    const char* highway = tags.get("highway");
    return default_road_width(highway ? highway : "", is_oneway(tags)) + lane_extras_width(tags);
}

SidewalkSides sidewalk_sides(const OsmTags& tags) {
    SidewalkSides sides;
    bool tagged = false;
    if (const char* s = tags.get("sidewalk")) {
        tagged = true;
        const std::string v = s;
        sides.left = v == "both" || v == "left" || v == "yes";
        sides.right = v == "both" || v == "right" || v == "yes";
    }
    // sidewalk:both / :left / :right refine or replace the plain tag.
    auto side_tag = [&](const char* key, bool& side) {
        if (const char* s = tags.get(key)) {
            tagged = true;
            side = std::strcmp(s, "yes") == 0;
        }
    };
    bool both = false;
    if (tags.get("sidewalk:both")) {
        side_tag("sidewalk:both", both);
        sides.left = sides.right = both;
    }
    side_tag("sidewalk:left", sides.left);
    side_tag("sidewalk:right", sides.right);
    if (tagged) return sides;
    static const std::set<std::string> with_sidewalks{"trunk",    "primary",      "secondary",
                                                      "tertiary", "unclassified", "residential"};
    const char* highway = tags.get("highway");
    const bool yes = highway && with_sidewalks.count(highway);
    return {yes, yes};
}

RoadGraph build_road_graph(const OsmData& osm, const Projection& projection,
                           const RoadParams& params, ParseReport& report, bool with_terrain) {
    const std::vector<WayPieces> ways = cut_into_pieces(osm, projection, params, with_terrain, report);
    const std::unordered_map<int64_t, int> degree = node_degrees(ways);
    RoadGraph graph = merge_collinear_runs(ways, degree, params, report);
    report.read(ReportKind::RoadEdges, static_cast<int64_t>(graph.edges.size()));
    return graph;
}

}  // namespace citygen
