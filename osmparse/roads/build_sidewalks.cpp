#include "osmparse/roads/build_sidewalks.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "osmparse/polygons/polygon_overlap.h"
#include "osmparse/polygons/ring_is_simple.h"
#include "osmparse/roads/narrow_roads.h"
#include "osmparse/roads/road_geometry.h"
#include "osmparse/roads/road_layout.h"

namespace citygen {

namespace {

constexpr double kSidewalkStep = 0.25;      // metres of width given up per step
constexpr double kMinSidewalkWidth = 0.75;  // narrower is no sidewalk
constexpr double kMaxRoadOverlap = 0.5;     // square metres of another road a piece may cover
constexpr double kMinPieceArea = 0.01;
constexpr double kMinTrimmedArea = 0.5;     // square metres: a piece trimmed smaller is dropped
constexpr int kMaxTrims = 4;

// A strip [a, b, c, d] has its end cuts a-d and b-c. On the inside of a tight curve (a
// small roundabout's island) the outline's cuts cross before the strip ends: the strip
// is then the triangle from its carriageway side (a-b, or c-d) up to the crossing.
Ring untwist_strip(const Ring& q, bool carriageway_first) {
    const Vec2 a = q[0], b = q[1], c = q[2], d = q[3];
    if (!segments_intersect(a, d, b, c)) return q;
    const Vec2 ad = d - a, bc = c - b;
    const double den = cross(ad, bc);
    if (std::fabs(den) < 1e-12) return q;
    const Vec2 x = a + ad * (cross(b - a, bc) / den);
    return carriageway_first ? Ring{a, b, x} : Ring{x, c, d};
}

// A clipped ring without repeated points, spikes or collinear points (where clipping
// ran along an edge).
Ring clean_piece(const Ring& ring) { return clean_ring(ring, RingCleaning::SpikesAndCollinear); }

// The part of `piece` off the road pieces it lies on: for the road piece it overlaps
// most, the piece is cut along whichever edge of that road piece (or of its convex hull,
// for a joint) keeps the most of it, and so on while it overlaps any by more than the
// tolerance. Cutting on one line keeps the piece in one piece.
Ring trim_off_roads(Ring piece, const BuildingIndex& roads) {
    for (int round = 0; round < kMaxTrims && piece.size() >= 3; ++round) {
        double most = kRoadBuildingOverlapTolerance;
        int worst = -1;
        roads.for_each_near(bounds_of(piece), [&](uint32_t i) {
            const double a = overlap_area(piece, roads.polygon(i));
            if (a > most) most = a, worst = static_cast<int>(i);
        });
        if (worst < 0) break;
        const Ring& outer = *roads.polygon(worst).outer;
        const Ring road = ring_is_convex(outer) ? outer : convex_hull(outer);
        Ring best;
        double best_area = 0;
        for (size_t e = 0, m = road.size(); e < m; ++e) {
            const Vec2 a = road[e], b = road[(e + 1) % m];
            Ring kept = clean_piece(clip_to_half_planes(piece, {{b, a}}));  // the side away from the road
            const double area = kept.size() >= 3 ? signed_area(kept) : 0;
            if (area > best_area + 1e-9) best_area = area, best = std::move(kept);
        }
        piece = std::move(best);
    }
    return piece;
}

struct Frame {
    Vec2 from, to, d, n;
};
Frame frame_of(const RoadGraphEdge& e) {
    const Vec2 d = normalize(e.to - e.from);
    return {e.from, e.to, d, perp_left(d)};
}

// Step 1: sidewalk width per side, narrowed where the band would reach into a building.
// The edges are searched in parallel and reported in order.
std::vector<SideWidths> sidewalk_widths(const RoadGraph& graph, const BuildingIndex& buildings,
                                        const SidewalkParams& params, ParseReport& report) {
    std::vector<SideWidths> walk(graph.edges.size());  // the width found, or below kMinSidewalkWidth: no room
    tbb::parallel_for(tbb::blocked_range<size_t>(0, graph.edges.size(), 256), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t e = r.begin(); e != r.end(); ++e) {
            const RoadGraphEdge& edge = graph.edges[e];
            for (int side = 0; side < 2; ++side) {
                if (!(side == 0 ? edge.sidewalk_left : edge.sidewalk_right)) continue;
                double w = params.width;
                for (; w >= kMinSidewalkWidth; w -= kSidewalkStep) {
                    const Frame f = frame_of(edge);
                    const double h = 0.5 * edge.width;
                    const Vec2 off = side == 0 ? f.n : f.n * -1.0;
                    Ring band{f.from + off * h, f.to + off * h, f.to + off * (h + w), f.from + off * (h + w)};
                    if (signed_area(band) < 0) band = {band[3], band[2], band[1], band[0]};
                    double largest = 0;
                    buildings.overlap(band, &largest);
                    if (largest <= kRoadBuildingOverlapTolerance) break;
                }
                (side == 0 ? walk[e].left : walk[e].right) = w;
            }
        }
    });
    for (size_t e = 0; e < graph.edges.size(); ++e) {
        const RoadGraphEdge& edge = graph.edges[e];
        for (int side = 0; side < 2; ++side) {
            if (!(side == 0 ? edge.sidewalk_left : edge.sidewalk_right)) continue;
            double& w = side == 0 ? walk[e].left : walk[e].right;
            if (w < kMinSidewalkWidth) {
                report.dropped(ReportKind::SidewalkSides, ReportReason::NoRoomBesideBuilding);
                w = 0;
                continue;
            }
            if (w < params.width) report.note(ReportKind::SidewalkSides, ReportReason::NarrowedBesideBuilding);
            report.kept(ReportKind::SidewalkSides);
        }
    }
    return walk;
}

// A sidewalk piece as steps 2 and 3 cut it, before its checks. `in_cleared_band`: a strip
// within the side's band, already cleared of buildings.
struct Piece {
    SidewalkKind kind;
    Ring polygon;
    int road, joint;
    bool in_cleared_band;
};

// What steps 2 and 3 share: the carriageway's end cuts (`in_*_cut`), its outline (`out`,
// which has the carriageway's nodes, ends and joins: lay_out_outline takes them over), and
// the pieces they cut.
struct SidewalkWork {
    const RoadGraph& graph;
    const RoadSurface& surface;
    std::vector<SideWidths> inner, walk, outer;
    std::vector<EdgeEndCut> in_from_cut, in_to_cut;
    std::vector<bool> joint_at_from, joint_at_to;  // per edge: its end lies at a joint
    RoadLayout out;                                // its nodes: only the joints'
    std::vector<Piece> pieces;

    void emit(SidewalkKind kind, Ring polygon, int road, int joint, bool in_cleared_band) {
        pieces.push_back({kind, std::move(polygon), road, joint, in_cleared_band});
    }
};

// How a piece fared in its checks (step 4), in the order the report counts them.
enum class Verdict { NotAPiece, Tangled, OverlapsBuilding, OnAnotherRoad, Kept };
struct Checked {
    Verdict verdict = Verdict::NotAPiece;
    bool trimmed = false;  // its part off the roads replaced it
};

// Step 4, for one piece: the checks, which read only the indexes (pieces are checked in parallel).
Checked check_piece(Piece& piece, const BuildingIndex& buildings, const BuildingIndex& road_index) {
    Checked out;
    Ring& polygon = piece.polygon;
    // Nothing between carriageway and outline (e.g. where a road without sidewalks
    // cuts through): not a piece at all.
    if (polygon.size() < 3 || std::fabs(signed_area(polygon)) < kMinPieceArea) return out;
    if (signed_area(polygon) < 0 || !ring_is_simple(polygon)) {
        out.verdict = Verdict::Tangled;
        return out;
    }
    double largest = 0;
    if (!piece.in_cleared_band) buildings.overlap(polygon, &largest);
    if (largest > kRoadBuildingOverlapTolerance) {
        out.verdict = Verdict::OverlapsBuilding;
        return out;
    }
    road_index.overlap(polygon, &largest);
    // Where roads lie closer than their sidewalks are wide (close or overlapping
    // roads, the inside of a hairpin), the piece keeps only its part off them.
    if (largest > kRoadBuildingOverlapTolerance) {
        Ring trimmed = trim_off_roads(polygon, road_index);
        if (trimmed.size() >= 3 && signed_area(trimmed) >= kMinTrimmedArea && ring_is_simple(trimmed)) {
            out.trimmed = true;
            polygon = std::move(trimmed);
            road_index.overlap(polygon, &largest);
        }
    }
    out.verdict = largest > kMaxRoadOverlap ? Verdict::OnAnotherRoad : Verdict::Kept;
    return out;
}

// Step 4: every piece checked (in parallel), then counted and kept in the order cut.
std::vector<Sidewalk> check_pieces(std::vector<Piece> pieces, const BuildingIndex& buildings,
                                   const BuildingIndex& road_index,
                                   const SidewalkParams& params, ParseReport& report) {
    std::vector<Checked> checked(pieces.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, pieces.size(), 64), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i)
            checked[i] = check_piece(pieces[i], buildings, road_index);
    });
    std::vector<Sidewalk> result;
    result.reserve(pieces.size());  // most are kept
    for (size_t i = 0; i < pieces.size(); ++i) {
        Piece& piece = pieces[i];
        const ReportKind what =
            piece.kind == SidewalkKind::Strip ? ReportKind::SidewalkStrips : ReportKind::SidewalkCorners;
        const Checked& c = checked[i];
        if (c.verdict == Verdict::NotAPiece) continue;
        report.read(what);
        if (c.trimmed) report.note(what, ReportReason::TrimmedOffRoad);
        switch (c.verdict) {
            case Verdict::Tangled: report.dropped(what, ReportReason::DegenerateTangledJunction); break;
            case Verdict::OverlapsBuilding: report.dropped(what, ReportReason::OverlapsBuilding); break;
            case Verdict::OnAnotherRoad: report.dropped(what, ReportReason::LiesOnAnotherRoad); break;
            default:
                report.kept(what);
                result.push_back({piece.kind, std::move(piece.polygon), piece.road, piece.joint, params.curb_height});
        }
    }
    return result;
}

// Step 2: strips along every edge side with a sidewalk, between the carriageway's side
// line and the outline's.
void add_strips(SidewalkWork& w) {
    const size_t n = w.graph.edges.size();
    auto strip_cut = [&](size_t e, bool at_from, bool left_of_leaving, double& t_in, double& t_out) {
        const EdgeEndCut& ci = at_from ? w.in_from_cut[e] : w.in_to_cut[e];
        const EdgeEndCut& co = at_from ? w.out.from_cut[e] : w.out.to_cut[e];
        t_in = left_of_leaving ? ci.t_left : ci.t_right;
        t_out = left_of_leaving ? co.t_left : co.t_right;
        // Where a strip ends at a joint both its lines stop at the outline's square cut: the
        // strip starts where the outline's joint ends; beside the carriageway's joint arm it
        // lies outside the carriageway, so this is safe even where the carriageway's cut
        // reaches further.
        if (at_from ? w.joint_at_from[e] : w.joint_at_to[e]) t_in = t_out;
    };
    const std::vector<SideWidths> &inner = w.inner, &outer = w.outer;
    for (size_t e = 0; e < n; ++e) {
        const int road = w.surface.road_of_edge[e];
        if (road < 0) continue;
        const Frame f = frame_of(w.graph.edges[e]);
        if (w.walk[e].left > 0) {
            double s_in, s_out, e_in, e_out;
            strip_cut(e, true, true, s_in, s_out);
            strip_cut(e, false, false, e_in, e_out);
            const bool in_band = std::min({s_in, s_out, e_in, e_out}) >= 0;
            w.emit(SidewalkKind::Strip,
                   untwist_strip({f.from + f.n * inner[e].left + f.d * s_in, f.to + f.n * inner[e].left - f.d * e_in,
                                  f.to + f.n * outer[e].left - f.d * e_out, f.from + f.n * outer[e].left + f.d * s_out},
                                 true),
                   road, -1, in_band);
        }
        if (w.walk[e].right > 0) {
            double s_in, s_out, e_in, e_out;
            strip_cut(e, true, false, s_in, s_out);
            strip_cut(e, false, true, e_in, e_out);
            const bool in_band = std::min({s_in, s_out, e_in, e_out}) >= 0;
            w.emit(SidewalkKind::Strip,
                   untwist_strip({f.from - f.n * outer[e].right + f.d * s_out, f.to - f.n * outer[e].right - f.d * e_out,
                                  f.to - f.n * inner[e].right - f.d * e_in, f.from - f.n * inner[e].right + f.d * s_in},
                                 false),
                   road, -1, in_band);
        }
    }
}

// Step 3: corner pieces. In each gap of a joint, the part of the outline's joint polygon
// outside both carriageways, i.e. beyond the left line of one road and the right line
// of the next. Where the gap is wider than a half turn that region is not convex, so it
// is cut in two along the gap's bisector.
void add_corners(SidewalkWork& w) {
    std::map<int64_t, int> joint_of_node;
    for (size_t j = 0; j < w.surface.joints.size(); ++j) joint_of_node[w.surface.joints[j].osm.id] = static_cast<int>(j);
    auto dir_of = [&](const NodeLayout::End& end) {
        const RoadGraphEdge& g = w.graph.edges[end.edge];
        return normalize(end.at_from ? g.to - g.from : g.from - g.to);
    };
    auto half_of = [&](const NodeLayout::End& end, bool left) {
        const SideWidths& s = w.inner[end.edge];
        return end.at_from == left ? s.left : s.right;
    };
    for (const NodeLayout& node : w.out.nodes) {  // the outline's joints: the carriageway's ends
        auto it = joint_of_node.find(node.node);
        const int joint = it == joint_of_node.end() ? -1 : it->second;
        const size_t m = node.ends.size();
        for (size_t i = 0; i < m; ++i) {
            const size_t j = (i + 1) % m;
            const NodeLayout::End &ei = node.ends[i], &ej = node.ends[j];
            // The gap lies on i's left and j's right (relative to leaving the node).
            const double walk_i = ei.at_from ? w.walk[ei.edge].left : w.walk[ei.edge].right;
            const double walk_j = ej.at_from ? w.walk[ej.edge].right : w.walk[ej.edge].left;
            if (walk_i <= 0 && walk_j <= 0) continue;
            const Vec2 di = dir_of(ei), dj = dir_of(ej);
            const Vec2 pi = ei.origin + perp_left(di) * half_of(ei, true);
            const Vec2 pj = ej.origin - perp_left(dj) * half_of(ej, false);
            const std::pair<Vec2, Vec2> beyond_i{pi, pi + di}, beyond_j{pj, pj - dj};
            const double gap = gap_angle(di, dj);
            if (gap < kStraightGap) {
                w.emit(SidewalkKind::Corner, clean_piece(clip_to_half_planes(node.joint, {beyond_i, beyond_j})), -1, joint,
                       false);
            } else {
                const double half = 0.5 * gap;
                const Vec2 bisector{di.x * std::cos(half) - di.y * std::sin(half), di.x * std::sin(half) + di.y * std::cos(half)};
                const Vec2 centre = node.position;
                w.emit(SidewalkKind::Corner,
                       clean_piece(clip_to_half_planes(node.joint, {beyond_i, {centre + bisector, centre}})), -1, joint, false);
                w.emit(SidewalkKind::Corner,
                       clean_piece(clip_to_half_planes(node.joint, {beyond_j, {centre, centre + bisector}})), -1, joint, false);
            }
        }
    }
}

}  // namespace

std::vector<Sidewalk> build_sidewalks(const RoadGraph& graph, RoadSurface& surface,
                                      const std::vector<Building>& buildings,
                                      const SidewalkParams& params, double miter_limit,
                                      ParseReport& report) {
    const BuildingIndex building_index(buildings);
    const size_t n = graph.edges.size();
    const std::vector<SideWidths> inner = carriageway_widths(graph);
    std::vector<SideWidths> walk = sidewalk_widths(graph, building_index, params, report), outer(n);
    for (size_t e = 0; e < n; ++e) outer[e] = {inner[e].left + walk[e].left, inner[e].right + walk[e].right};
    // The strips read the carriageway's end cuts; the rest of its layout (nodes, ends, joins,
    // merged junctions) is what the outline is shaped on: lay_out_outline takes it over.
    SidewalkWork work{graph, surface, inner, std::move(walk), std::move(outer),
                      std::move(surface.layout.from_cut), std::move(surface.layout.to_cut), {}, {}, {}, {}};
    work.out = lay_out_outline(graph, std::move(surface.layout), work.outer, miter_limit);
    surface.layout = {};
    // What the strips and corners read of the outline: where each edge ends at a joint, the
    // end cuts, and the joints' nodes (their ends and polygon). The rest (its quads, the
    // other nodes, merged members, gap points) is freed before any piece is cut.
    work.out.quads = {};
    work.joint_at_from.assign(n, false);
    work.joint_at_to.assign(n, false);
    size_t joints = 0, gaps = 0;
    for (const NodeLayout& node : work.out.nodes) {
        if (node.kind != JoinKind::Joint) continue;
        for (const NodeLayout::End& end : node.ends) (end.at_from ? work.joint_at_from : work.joint_at_to)[end.edge] = true;
        gaps += node.ends.size();
        joints += node.joint.empty() ? 0 : 1;
    }
    std::vector<NodeLayout> joint_nodes;
    joint_nodes.reserve(joints);
    for (NodeLayout& node : work.out.nodes) {
        if (node.kind != JoinKind::Joint || node.joint.empty()) continue;
        std::vector<int64_t>().swap(node.members);
        for (NodeLayout::End& end : node.ends) std::vector<Vec2>().swap(end.gap_points);
        joint_nodes.push_back(std::move(node));
    }
    work.out.nodes = std::move(joint_nodes);
    // At most two strips per edge and two corners per gap of a joint: reserved at once, the
    // pieces are not copied as they grow (grown by doubling, they needed the heap to grow).
    work.pieces.reserve(2 * n + 2 * gaps);
    add_strips(work);
    work.in_from_cut = {};
    work.in_to_cut = {};
    work.out.from_cut = {};
    work.out.to_cut = {};
    add_corners(work);
    work.out = {};  // the outline is cut into the pieces: free it before they are checked
    // The surface's quads and joints, to keep sidewalks off.
    const BuildingIndex road_index(surface_polygons(surface.roads, surface.joints));
    return check_pieces(std::move(work.pieces), building_index, road_index, params, report);
}

}  // namespace citygen
