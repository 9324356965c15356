#include "osmparse/roads/lay_out_lanes.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <string>
#include <unordered_map>

#include "osmparse/core/osm_units.h"
#include "osmparse/polygons/polygon_overlap.h"
#include "osmparse/roads/build_road_graph.h"

namespace citygen {

namespace {

constexpr int kMaxLanes = 12;

// A lane count tag and the note that counts it when it is present but unusable.
struct CountTag {
    const char* key;
    ReportReason unusable;
};
constexpr CountTag kLanes{"lanes", ReportReason::LaneCountUnusable};
constexpr CountTag kLanesForward{"lanes:forward", ReportReason::ForwardLaneCountUnusable};
constexpr CountTag kLanesBackward{"lanes:backward", ReportReason::BackwardLaneCountUnusable};

std::optional<int> count_tag(const OsmTags& tags, CountTag tag, ParseReport* report) {
    const char* text = tags.get(tag.key);
    if (!text) return std::nullopt;
    const std::optional<double> n = parse_osm_count(text);
    if (n && *n >= 0 && *n <= kMaxLanes) return static_cast<int>(*n);
    if (report) report->note(ReportKind::RoadLanes, tag.unusable);
    return std::nullopt;
}

// Entries of a turn:lanes value ("left|through|through;right" has three).
std::optional<int> turn_lanes(const OsmTags& tags, const char* key) {
    const char* text = tags.get(key);
    if (!text || !*text) return std::nullopt;
    return 1 + static_cast<int>(std::count(text, text + std::strlen(text), '|'));
}

bool is_one_of(const char* v, std::initializer_list<const char*> values) {
    if (!v) return false;
    for (const char* x : values)
        if (!std::strcmp(v, x)) return true;
    return false;
}

// Sides (0, 1 or 2) a lane-type tag family gives: key=value (both), key:both, key:left, key:right.
int sides_with(const OsmTags& tags, const std::string& key, std::initializer_list<const char*> values) {
    if (is_one_of(tags.get(key.c_str()), values)) return 2;
    if (is_one_of(tags.get((key + ":both").c_str()), values)) return 2;
    return is_one_of(tags.get((key + ":left").c_str()), values) + is_one_of(tags.get((key + ":right").c_str()), values);
}

}  // namespace

double lane_extras_width(const OsmTags& tags) {
    const int cycle = sides_with(tags, "cycleway", {"lane"});
    const int bus = sides_with(tags, "busway", {"lane"});
    const int parking = std::max(sides_with(tags, "parking", {"lane", "street_side"}),
                                 sides_with(tags, "parking:lane", {"parallel", "diagonal", "perpendicular"}));
    return 1.5 * cycle + 3.0 * bus + 2.0 * parking;
}

LaneLayout lane_layout(const OsmTags& tags, RoadClass road_class, double width, ParseReport* report) {
    LaneLayout out;
    const char* oneway_tag = tags.get("oneway");
    const bool reversed = oneway_tag && !std::strcmp(oneway_tag, "-1");
    const bool oneway = is_oneway(tags);
    std::optional<int> fwd = count_tag(tags, kLanesForward, report), bwd = count_tag(tags, kLanesBackward, report);
    std::optional<int> total = count_tag(tags, kLanes, report);
    if (!total) total = turn_lanes(tags, "turn:lanes");
    if (!fwd) fwd = turn_lanes(tags, "turn:lanes:forward");
    if (!bwd) bwd = turn_lanes(tags, "turn:lanes:backward");
    if (oneway) {
        const int n = std::max(1, total.value_or(fwd.value_or(road_class <= RoadClass::Trunk ? 2 : 1)));
        out.forward = reversed ? 0 : n;
        out.backward = reversed ? n : 0;
    } else if (fwd || bwd) {
        out.forward = fwd.value_or(std::max(1, total.value_or(2) - bwd.value_or(1)));
        out.backward = bwd.value_or(std::max(1, total.value_or(2) - out.forward));
    } else if (total) {
        out.forward = std::max(1, (*total + 1) / 2);
        out.backward = std::max(0, *total - out.forward);
    } else {
        const bool single = road_class == RoadClass::Service || road_class == RoadClass::LivingStreet ||
                            road_class == RoadClass::Other;
        out.forward = 1;
        out.backward = single ? 0 : 1;
        if (road_class == RoadClass::Motorway) out.forward = out.backward = 2;
    }
    const bool cycle_both = is_one_of(tags.get("cycleway"), {"lane"}) || is_one_of(tags.get("cycleway:both"), {"lane"});
    out.cycle_left = cycle_both || is_one_of(tags.get("cycleway:left"), {"lane"});
    out.cycle_right = cycle_both || is_one_of(tags.get("cycleway:right"), {"lane"});
    const int lanes = out.forward + out.backward;
    const bool two_way = out.forward > 0 && out.backward > 0;
    if (two_way && lanes >= 2 && width >= 5) {
        if (lanes >= 4) out.centre = CentreLine::Double;
        else if (road_class <= RoadClass::Secondary) out.centre = CentreLine::Solid;
        else out.centre = CentreLine::Dashed;
    }
    out.edge_lines = road_class <= RoadClass::Secondary && width >= 5;
    return out;
}

void lay_out_lanes(std::vector<RoadEdge>& roads, const OsmData& osm, ParseReport& report) {
    std::unordered_map<int64_t, const OsmTags*> tags_of;
    for (const OsmWay& w : osm.highways) tags_of.emplace(w.id, &w.tags);
    std::unordered_map<int64_t, LaneLayout> done;  // per way: tags are the same along it
    for (RoadEdge& r : roads) {
        auto it = tags_of.find(r.osm.id);
        if (it == tags_of.end()) continue;
        auto cached = done.find(r.osm.id);
        if (cached == done.end())
            cached = done.emplace(r.osm.id, lane_layout(*it->second, r.road_class, r.width, &report)).first;
        LaneLayout layout = cached->second;
        // A road narrowed beside a building keeps its lanes but may lose its centre line.
        if (r.width < 5) layout.centre = CentreLine::None, layout.edge_lines = false;
        r.lanes_forward = layout.forward;
        r.lanes_backward = layout.backward;
        r.centre_line = layout.centre;
        r.edge_lines = layout.edge_lines;
        // A cycle lane needs 1.5 m beside at least 2.5 m per motor lane.
        const double room = r.width - 2.5 * std::max(1, layout.forward + layout.backward);
        r.cycle_lane_left = layout.cycle_left && room >= 1.5 * (1 + layout.cycle_right);
        r.cycle_lane_right = layout.cycle_right && room >= 1.5 * (1 + layout.cycle_left);
        report.kept(ReportKind::RoadLanes, layout.forward + layout.backward);
    }
}

std::vector<Crossing> place_crossings(const OsmData& osm, const Projection& projection, const Scene& scene,
                                      ParseReport& report) {
    std::vector<PolygonRef> quads, joints;
    for (const RoadEdge& r : scene.roads) quads.push_back({&r.quad});
    for (const Joint& j : scene.joints) joints.push_back({&j.polygon});
    const BuildingIndex index(std::move(quads), 50);
    const BuildingIndex joint_index(std::move(joints), 50);
    std::vector<Crossing> out;
    for (const OsmNode& node : osm.road_marks) {
        const bool signal = node.tags.has("highway", "traffic_signals");
        const ReportKind kind = signal ? ReportKind::StopLines : ReportKind::ZebraCrossings;
        if (!signal) {
            const char* crossing = node.tags.get("crossing");
            const char* markings = node.tags.get("crossing:markings");
            const bool marked = is_one_of(crossing, {"zebra", "marked", "uncontrolled"}) ||
                                (markings && std::strcmp(markings, "no") != 0) || node.tags.has("crossing_ref", "zebra");
            if (!marked) continue;
        }
        report.read(kind);
        const Vec2 p = projection.to_local(node.location.lat, node.location.lon);
        Box2 box;
        box.extend(p - Vec2(15, 15));
        box.extend(p + Vec2(15, 15));
        int best = -1;
        double best_distance = 1e300, best_t = 0;
        index.for_each_near(box, [&](uint32_t i) {
            const RoadEdge& r = scene.roads[i];
            const Vec2 a = r.centreline.front(), b = r.centreline.back(), ab = b - a;
            const double t = std::clamp(dot(p - a, ab) / std::max(dot(ab, ab), 1e-12), 0.0, 1.0);
            const double d = length(p - (a + ab * t));
            if (d <= 0.5 * r.width + 1 && d < best_distance && point_in_ring(a + ab * t, r.quad)) {
                best = static_cast<int>(i);
                best_distance = d;
                best_t = t;
            }
        });
        if (best < 0) {
            report.dropped(kind,
                           joint_index.contains(p) ? ReportReason::OnJunctionPolygon : ReportReason::NotOnDrawnRoad);
            continue;
        }
        const RoadEdge& r = scene.roads[best];
        Crossing c;
        c.osm = {OsmType::Node, node.id};
        c.road = best;
        c.position = r.centreline.front() + (r.centreline.back() - r.centreline.front()) * best_t;
        c.kind = signal ? CrossingKind::StopLine : CrossingKind::Zebra;
        if (signal && r.lanes_forward > 0 && r.lanes_backward > 0)
            c.side = best_t >= 0.5 ? RoadSide::Right : RoadSide::Left;  // traffic towards the nearer end
        out.push_back(c);
    }
    std::sort(out.begin(), out.end(), [](const Crossing& a, const Crossing& b) { return a.osm < b.osm; });
    size_t zebras = 0;
    for (const Crossing& c : out) zebras += c.kind == CrossingKind::Zebra;
    report.kept(ReportKind::ZebraCrossings, static_cast<int64_t>(zebras));
    report.kept(ReportKind::StopLines, static_cast<int64_t>(out.size() - zebras));
    return out;
}

}  // namespace citygen
