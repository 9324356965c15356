#include "road_layout.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <set>

#include "polygon_overlap.h"

namespace citygen {

namespace {

constexpr double kMaxCutFraction = 0.45;  // no cut reaches past this share of an edge
constexpr double kStraightCos = 0.99996;  // cos(0.5 deg): closer to straight needs no miter
constexpr double kDedupe = 1e-4;          // metres: closer points are one point
constexpr double kMinJointArea = 1e-3;    // square metres
constexpr double kCrossEps = 1e-4;        // cut segments touching at their ends do not cross
constexpr double kMaxJunctionSpan = 25;   // metres: junctions merged into one joint stay this small

// Intersection of p1 + s*d1 and p2 + u*d2; false when (nearly) parallel.
bool intersect_lines(Vec2 p1, Vec2 d1, Vec2 p2, Vec2 d2, double& s, double& u) {
    const double den = cross(d1, d2);
    if (std::fabs(den) < 1e-9) return false;
    const Vec2 w = p2 - p1;
    s = cross(w, d2) / den;
    u = cross(w, d1) / den;
    return true;
}

// One edge as seen from the node it leaves (its origin).
struct EndGeometry {
    Vec2 origin, dir, normal;  // leaving the node; normal points left
    double half_left, half_right;
    double max_cut;
    double limit = 0;          // the furthest any cut may go before the quad would fold
    Vec2 left_at(double t) const { return origin + normal * half_left + dir * t; }
    Vec2 right_at(double t) const { return origin - normal * half_right + dir * t; }
};

EndGeometry end_geometry(const RoadGraphEdge& e, SideWidths w, bool at_from) {
    EndGeometry g;
    const Vec2 along = at_from ? e.to - e.from : e.from - e.to;
    g.origin = at_from ? e.from : e.to;
    g.dir = normalize(along);
    g.normal = perp_left(g.dir);
    g.half_left = at_from ? w.left : w.right;
    g.half_right = at_from ? w.right : w.left;
    g.max_cut = kMaxCutFraction * length(along);
    return g;
}

void push_distinct(Ring& ring, Vec2 p) {
    if (ring.empty() || length(ring.back() - p) > kDedupe) ring.push_back(p);
}

// Cuts on the miter of a degree-2 node; false when the miter is not acceptable.
bool miter_cuts(Vec2 p, const EndGeometry& a, const EndGeometry& b, double miter_limit, bool forced,
                EdgeEndCut& cut_a, EdgeEndCut& cut_b) {
    if (dot(a.dir, b.dir) < -kStraightCos) {  // straight on: square cuts through the node
        cut_a = cut_b = {0, 0};
        return true;
    }
    double s_ab, u_ab, s_ba, u_ba;
    if (!intersect_lines(a.left_at(0), a.dir, b.right_at(0), b.dir, s_ab, u_ab) ||
        !intersect_lines(b.left_at(0), b.dir, a.right_at(0), a.dir, s_ba, u_ba))
        return false;
    cut_a = {s_ab, u_ba};
    cut_b = {s_ba, u_ab};
    const double reach = miter_limit * std::max({a.half_left, a.half_right, b.half_left, b.half_right});
    const bool within_limit = length(a.left_at(s_ab) - p) <= reach && length(b.left_at(s_ba) - p) <= reach;
    auto fits = [](double t, const EndGeometry& g) { return std::fabs(t) <= g.max_cut; };
    const bool fits_edges = fits(s_ab, a) && fits(u_ba, a) && fits(s_ba, b) && fits(u_ab, b);
    if (forced) {
        auto clamp = [](double& t, const EndGeometry& g) { t = std::clamp(t, -g.max_cut, g.max_cut); };
        clamp(cut_a.t_left, a); clamp(cut_a.t_right, a); clamp(cut_b.t_left, b); clamp(cut_b.t_right, b);
        return true;
    }
    return within_limit && fits_edges;
}

// Near-parallel neighbours meet far out (half width / tan(half the angle)); a joint
// reaching that far would swallow the roads, so corners are cut at this distance and
// the two quads overlap beyond it, as the roads themselves do.
constexpr double kCornerReachInHalfWidths = 3;
double corner_reach(const EndGeometry& i, const EndGeometry& j) {
    return kCornerReachInHalfWidths * std::max({i.half_left, i.half_right, j.half_left, j.half_right});
}

// How far each end of a junction would have to be cut back for the offset lines of
// neighbouring edges to meet (unlimited by the edge's length).
double joint_demand(const std::vector<EndGeometry>& geo, size_t end) {
    const size_t k = geo.size();
    double demand = 0;
    for (size_t side = 0; side < 2; ++side) {
        const size_t i = side == 0 ? end : (end + k - 1) % k;  // gap on the left, then on the right
        const size_t j = (i + 1) % k;
        const EndGeometry &gi = geo[i], &gj = geo[j];
        double gap = std::atan2(cross(gi.dir, gj.dir), dot(gi.dir, gj.dir));
        if (gap <= 0) gap += 2 * kPi;
        if (gap >= kPi - 1e-3) continue;
        double s, u;
        if (!intersect_lines(gi.left_at(0), gi.dir, gj.right_at(0), gj.dir, s, u))
            continue;
        demand = std::max(demand, std::min(side == 0 ? s : u, corner_reach(gi, gj)));
    }
    return demand;
}

// Each edge's cut at a node and the joint's ring (thesis: sort by angle, intersect
// neighbouring offset lines), unfinished: finish_joint cuts the quads out of it once all
// cuts are known. Returns the ring, and where cuts cross a smaller fallback ring.
std::vector<Ring> layout_joint(NodeLayout& node, const std::vector<EndGeometry>& geo) {
    const size_t k = node.ends.size();
    std::vector<double> demand_left(k, 0), demand_right(k, 0);
    std::vector<bool> cut_short(k, false);  // the corner of gap (i, i+1) was not reached
    for (size_t i = 0; i < k; ++i) {
        const size_t j = (i + 1) % k;
        const EndGeometry &gi = geo[i], &gj = geo[j];
        node.ends[i].gap_points.clear();
        double gap = std::atan2(cross(gi.dir, gj.dir), dot(gi.dir, gj.dir));
        if (gap <= 0) gap += 2 * kPi;
        if (k == 1 || gap >= kPi - 1e-3) continue;  // open or straight side: a plain bevel
        double s, u;
        if (!intersect_lines(gi.left_at(0), gi.dir, gj.right_at(0), gj.dir, s, u))
            continue;
        // Near-parallel neighbours and short edges: the true corner lies too far out,
        // so the corner is cut short on both edges.
        const double s_full = s, u_full = u;
        s = std::clamp(s, 0.0, std::min(gi.max_cut, corner_reach(gi, gj)));
        u = std::clamp(u, 0.0, std::min(gj.max_cut, corner_reach(gi, gj)));
        cut_short[i] = s < s_full - kDedupe || u < u_full - kDedupe;
        demand_left[i] = s;
        demand_right[j] = u;
        node.ends[i].gap_points.push_back(gi.left_at(s));
        node.ends[i].gap_points.push_back(gj.right_at(u));
    }
    for (size_t i = 0; i < k; ++i) {
        NodeLayout::End& end = node.ends[i];
        end.trim = end.cut_left = end.cut_right = std::max(demand_left[i], demand_right[i]);
    }
    // Where a corner was cut short the two quads still overlap there, and between
    // their square cuts and the joint's chord a sliver would be left uncovered (or the
    // cuts even cross). Both are then cut on one common line across the pair,
    // perpendicular to the gap's bisector and beyond both square cuts: the joint ends
    // on that line, the two quads start on it (and overlap beyond, as the roads do).
    auto cuts_cross = [&](size_t i) {
        const size_t j = (i + 1) % k;
        const Vec2 ri = geo[i].right_at(node.ends[i].trim), li = geo[i].left_at(node.ends[i].trim);
        const Vec2 rj = geo[j].right_at(node.ends[j].trim), lj = geo[j].left_at(node.ends[j].trim);
        double s, u;
        return intersect_lines(ri, li - ri, rj, lj - rj, s, u) && s > kCrossEps && s < 1 - kCrossEps && u > kCrossEps && u < 1 - kCrossEps;
    };
    std::vector<bool> common_cut(k, false);
    for (size_t i = 0; i < k && k > 1; ++i) {
        const size_t j = (i + 1) % k;
        if (!(cut_short[i] || cuts_cross(i)) || common_cut[i] || common_cut[j] || (k > 2 && cuts_cross(j))) continue;
        // The least each end must keep cut: the corner on its other side (or the line
        // it already shares with its other neighbour).
        const size_t h = (i + k - 1) % k;
        const double least[2] = {common_cut[h] ? node.ends[i].trim : demand_right[i], demand_left[j]};
        // Candidate lines, each given by a point on it and its normal pointing away
        // from the node: perpendicular to the gap's bisector beyond both square cuts;
        // failing that (a short edge cannot be cut that far), the same beyond only
        // what each end must keep, or the square cut line of one end carried across
        // the other.
        struct Line { Vec2 point, normal; };
        std::vector<Line> candidates;
        const Vec2 b = normalize(geo[i].dir + geo[j].dir);
        if (dot(geo[i].dir, b) > 0.1 && dot(geo[j].dir, b) > 0.1) {
            for (bool from_trim : {true, false}) {
                double reach = -1e300;
                for (int e = 0; e < 2; ++e) {
                    const size_t end = e == 0 ? i : j;
                    const double t = from_trim ? node.ends[end].trim : least[e];
                    for (Vec2 p : {geo[end].right_at(t), geo[end].left_at(t)}) reach = std::max(reach, dot(p - node.position, b));
                }
                candidates.push_back({node.position + b * reach, b});
            }
        }
        candidates.push_back({geo[j].left_at(least[1]), geo[j].dir});
        candidates.push_back({geo[i].left_at(least[0]), geo[i].dir});
        bool found = false;
        double cuts[2][2];
        for (const Line& line : candidates) {
            bool fits = true;
            for (int e = 0; e < 2 && fits; ++e) {
                const size_t end = e == 0 ? i : j;
                const EndGeometry& g = geo[end];
                const double along = dot(g.dir, line.normal);
                if (along < 0.1) { fits = false; break; }
                // Distance along the end's side lines to the line: never short of the
                // end's square cut, never past what the edge can give.
                cuts[e][0] = dot(line.point - g.left_at(0), line.normal) / along;
                cuts[e][1] = dot(line.point - g.right_at(0), line.normal) / along;
                fits = std::min(cuts[e][0], cuts[e][1]) >= least[e] - kDedupe &&
                       std::max(cuts[e][0], cuts[e][1]) <= g.limit;
            }
            if (fits) { found = true; break; }
        }
        if (!found) continue;
        for (int e = 0; e < 2; ++e) {
            NodeLayout::End& end = node.ends[e == 0 ? i : j];
            end.cut_left = std::max(cuts[e][0], least[e]);
            end.cut_right = std::max(cuts[e][1], least[e]);
            end.trim = std::max(end.cut_left, end.cut_right);
        }
        common_cut[i] = true;
    }
    // Any crossing left (a chain of near-parallel roads): the ring takes the four cut
    // ends in the order they lie around the node (the two cuts are its diagonals), and
    // finish_joint cuts the two quads out of it.
    std::vector<bool> crosses(k, false);
    std::vector<Vec2> crossing(k);
    for (size_t i = 0; i < k && k > 1; ++i) {
        const size_t j = (i + 1) % k;
        // Only a gap under a half turn has a corner to cross at (with two ends, the same
        // two cuts would otherwise cross on both sides).
        if (common_cut[i] || cross(geo[i].dir, geo[j].dir) <= 0) continue;
        const Vec2 ri = geo[i].right_at(node.ends[i].cut_right), li = geo[i].left_at(node.ends[i].cut_left);
        const Vec2 rj = geo[j].right_at(node.ends[j].cut_right), lj = geo[j].left_at(node.ends[j].cut_left);
        double s, u;
        if (intersect_lines(ri, li - ri, rj, lj - rj, s, u) && s > kCrossEps && s < 1 - kCrossEps && u > kCrossEps && u < 1 - kCrossEps) {
            crosses[i] = true;
            crossing[i] = ri + (li - ri) * s;
        }
    }
    // With `at_crossing`, crossing cuts meet at their crossing point instead (smaller,
    // but it can leave a hole beside either quad): the fallback where cutting the quads
    // out of the larger ring fails.
    auto ring_with = [&](bool at_crossing) {
        Ring ring;
        for (size_t i = 0; i < k; ++i) {
            const NodeLayout::End& end = node.ends[i];
            const size_t prev = (i + k - 1) % k;
            if (!crosses[prev]) push_distinct(ring, geo[i].right_at(end.cut_right));
            else if (at_crossing) push_distinct(ring, crossing[prev]);
            if (crosses[i]) {
                if (at_crossing) {
                    push_distinct(ring, crossing[i]);
                } else {
                    push_distinct(ring, geo[(i + 1) % k].right_at(node.ends[(i + 1) % k].cut_right));
                    push_distinct(ring, geo[i].left_at(end.cut_left));
                }
                continue;
            }
            push_distinct(ring, geo[i].left_at(end.cut_left));
            if (!common_cut[i])
                for (Vec2 q : end.gap_points) push_distinct(ring, q);
        }
        return ring;
    };
    for (size_t i = 0; i < k; ++i)
        if (common_cut[i]) node.ends[i].gap_points.clear();  // the next end starts on the same line
    std::vector<Ring> rings{ring_with(false)};
    if (std::find(crosses.begin(), crosses.end(), true) != crosses.end()) rings.push_back(ring_with(true));
    return rings;
}

// A ring without repeated points or spikes (a vertex where the boundary runs out and
// straight back along itself).
Ring without_spikes(Ring ring) {
    Ring out;
    for (Vec2 p : ring) push_distinct(out, p);
    ring = std::move(out);
    while (ring.size() > 1 && length(ring.front() - ring.back()) <= kDedupe) ring.pop_back();
    for (bool removed = true; removed && ring.size() > 3;) {
        removed = false;
        for (size_t i = 0, m = ring.size(); i < m; ++i) {
            const Vec2 a = ring[(i + m - 1) % m], b = ring[i], c = ring[(i + 1) % m];
            if (std::fabs(cross(b - a, c - b)) < 1e-9 * (1 + length(b - a) * length(c - b)) && dot(b - a, c - b) < 0) {
                ring.erase(ring.begin() + static_cast<long>(i));
                removed = true;
                break;
            }
        }
    }
    return ring;
}

// The part of the CCW ring outside the convex CCW quad `q` into `out`, where the ring
// only dips into the quad (a joint beside a neighbour's short quad, or a corner cut short
// where two roads still overlap): each stretch inside is replaced by the quad's boundary,
// walked clockwise from where the ring enters to where it leaves. False when the ring
// does not reach into the quad (`out` is then not set).
bool cut_away_quad(const Ring& ring, const Ring& q, Ring& out) {
    constexpr double kInside = 1e-6;  // metres: closer to the quad's boundary is outside
    Vec2 unit[4];
    for (int e = 0; e < 4; ++e) unit[e] = normalize(q[(e + 1) % 4] - q[e]);
    auto depth = [&](Vec2 x, int e) { return cross(unit[e], x - q[e]) - kInside; };
    // Most rings lie wholly behind the quad's cut at their node (edge 3 at the edge's
    // `from` end, edge 1 at its `to` end), or outside another edge: nothing to cut.
    for (int e : {3, 1, 0, 2}) {
        bool outside = true;
        for (size_t i = 0; i < ring.size() && outside; ++i) outside = depth(ring[i], e) <= 0;
        if (outside) return false;
    }
    auto inside = [&](Vec2 x) {
        for (int e = 0; e < 4; ++e)
            if (depth(x, e) <= 0) return false;
        return true;
    };
    // The stretch [t0, t1] of segment a-b inside q, entering through edge e0 and leaving
    // through e1 (-1 where a, or b, is inside).
    auto stretch_inside = [&](Vec2 a, Vec2 b, double& t0, double& t1, int& e0, int& e1) {
        t0 = 0, t1 = 1, e0 = e1 = -1;
        for (int e = 0; e < 4; ++e) {
            const double fa = depth(a, e), fb = depth(b, e);
            if (fa <= 0 && fb <= 0) return false;
            if (fa <= 0 && fa / (fa - fb) > t0) t0 = fa / (fa - fb), e0 = e;
            if (fb <= 0 && fa / (fa - fb) < t1) t1 = fa / (fa - fb), e1 = e;
        }
        return t0 < t1;
    };
    const size_t m = ring.size();
    size_t start = m;
    for (size_t i = 0; i < m && start == m; ++i)
        if (!inside(ring[i])) start = i;
    out.clear();
    if (start == m) return true;  // wholly inside the quad
    int entered = -1;  // the quad edge the ring entered through, while inside
    bool cut = false;
    for (size_t k = 0; k < m; ++k) {
        const Vec2 a = ring[(start + k) % m], b = ring[(start + k + 1) % m];
        if (entered < 0) out.push_back(a);
        double t0, t1;
        int e0, e1;
        if (!stretch_inside(a, b, t0, t1, e0, e1)) continue;
        if (entered < 0) {
            if (e0 < 0) continue;  // numerically on the boundary
            out.push_back(a + (b - a) * t0);
            entered = e0;
            cut = true;
        }
        if (e1 >= 0) {
            for (int e = entered; e != e1; e = (e + 3) % 4) out.push_back(q[e]);
            out.push_back(a + (b - a) * t1);
            entered = -1;
        }
    }
    return cut;
}

// Finishes a joint once every quad is known: the parts of the joint's ring inside the
// quads of its own ends are cut away, so quads and joint meet edge to edge. Where that
// fails (rare tangles of short edges), the fallback ring, then the points sorted by angle
// around the node (a star-shaped polygon), then their convex hull are tried, and the
// one overlapping its quads least is kept.
void finish_joint(NodeLayout& node, const std::vector<Ring>& raw_rings, const std::vector<Ring>& quads) {
    node.joint.clear();
    node.joint_is_hull = false;
    auto valid = [](const Ring& ring) {
        return ring.size() >= 3 && signed_area(ring) > kMinJointArea && ring_is_simple(ring);
    };
    // Cuts the quads away where the ring reaches into them and adds up the overlap
    // left. Where a quad lies across the ring rather than dipping into it (a sliver of a
    // quad inside a tangle), cutting it away would split the joint: that quad then stays.
    auto apart = [&](Ring ring, double& overlap) {
        overlap = 0;
        Ring cut;
        for (const NodeLayout::End& end : node.ends) {
            const Ring& q = quads[end.edge];
            if (q.empty() || !cut_away_quad(ring, q, cut)) continue;
            cut = without_spikes(std::move(cut));
            if (valid(cut)) ring = std::move(cut);
            else overlap += clipped_area(ring, q);
        }
        return ring;
    };
    // Holes left beside a quad: of nine points just beyond its end, those neither in the
    // joint nor in another quad of the node.
    auto holes = [&](const Ring& joint) {
        int count = 0;
        for (const NodeLayout::End& end : node.ends) {
            const Ring& q = quads[end.edge];
            if (q.empty()) continue;
            const Vec2 c1 = end.at_from ? q[0] : q[1], c2 = end.at_from ? q[3] : q[2];
            const Vec2 beyond = normalize((c1 + c2) * 0.5 - (q[0] + q[1] + q[2] + q[3]) * 0.25) * 0.01;
            for (int s = 1; s < 10; ++s) {
                const Vec2 p = c1 + (c2 - c1) * (s / 10.0) + beyond;
                bool covered = point_in_ring(p, joint);
                for (const NodeLayout::End& other : node.ends)
                    covered = covered || (other.edge != end.edge && !quads[other.edge].empty() &&
                                          point_in_ring(p, quads[other.edge]));
                count += !covered;
            }
        }
        return count;
    };
    // The candidates in order: the exact ring, the fallback ring where cuts cross, the
    // star, the convex hull. The first that fits its quads exactly once they are cut
    // out is kept; failing that, the one with the least overlap and fewest holes.
    constexpr double kHoleCost = 0.1;  // square metres of overlap one hole sample weighs
    double least = 1e300;
    const Ring ring = without_spikes(raw_rings[0]);
    auto consider = [&](const Ring& candidate, bool exact, bool is_hull) {
        if (!valid(candidate)) return false;
        double overlap;
        Ring joint = apart(candidate, overlap);
        // The exact ring leaves holes only where a quad could not be cut out of it.
        const bool may_leave_holes = overlap > 0 || !exact;
        const double badness = (overlap < kMinJointArea ? 0 : overlap) + (may_leave_holes ? kHoleCost * holes(joint) : 0);
        if (badness >= least) return false;
        least = badness;
        node.joint = std::move(joint);
        node.joint_is_hull = is_hull;
        return badness == 0;
    };
    if (consider(ring, true, false)) return;
    for (size_t r = 1; r < raw_rings.size(); ++r)
        if (consider(without_spikes(raw_rings[r]), false, false)) return;
    Ring star = ring;
    std::sort(star.begin(), star.end(), [&](Vec2 a, Vec2 b) {
        return std::atan2(a.y - node.position.y, a.x - node.position.x) <
               std::atan2(b.y - node.position.y, b.x - node.position.x);
    });
    if (consider(star, false, true)) return;
    consider(convex_hull(ring), false, true);
}

bool quad_is_valid(const Ring& q) {
    return q.size() == 4 && ring_is_convex(q) && signed_area(q) > 1e-3;
}

}  // namespace

Ring quad_for_cuts(const RoadGraphEdge& e, SideWidths w, EdgeEndCut from, EdgeEndCut to) {
    const Vec2 d = normalize(e.to - e.from), n = perp_left(d);
    return {e.from - n * w.right + d * from.t_right, e.to - n * w.right - d * to.t_left,
            e.to + n * w.left - d * to.t_right, e.from + n * w.left + d * from.t_left};
}

Ring convex_hull(std::vector<Vec2> p) {
    std::sort(p.begin(), p.end(), [](Vec2 a, Vec2 b) { return a.x != b.x ? a.x < b.x : a.y < b.y; });
    p.erase(std::unique(p.begin(), p.end()), p.end());
    if (p.size() < 3) return p;
    Ring h(2 * p.size());
    size_t k = 0;
    for (size_t i = 0; i < p.size(); ++i) {
        while (k >= 2 && cross(h[k - 1] - h[k - 2], p[i] - h[k - 2]) <= 0) --k;
        h[k++] = p[i];
    }
    for (size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
        while (k >= t && cross(h[k - 1] - h[k - 2], p[i] - h[k - 2]) <= 0) --k;
        h[k++] = p[i];
    }
    h.resize(k - 1);
    return h;
}

RoadLayout layout_road_polygons(const RoadGraph& graph, const std::vector<SideWidths>& widths,
                                double miter_limit, const RoadLayout* follow,
                                const std::function<bool(int64_t)>& only) {
    const size_t n = graph.edges.size();
    RoadLayout out;
    out.from_cut.assign(n, {});
    out.to_cut.assign(n, {});
    out.quads.assign(n, {});
    out.absorbed.assign(n, false);

    std::map<int64_t, NodeLayout> nodes;
    for (uint32_t e = 0; e < n; ++e) {
        const RoadGraphEdge& edge = graph.edges[e];
        NodeLayout& a = nodes[edge.from_node];
        a.node = edge.from_node;
        a.position = edge.from;
        a.ends.push_back({e, true, edge.from, 0, 0, 0, {}});
        NodeLayout& b = nodes[edge.to_node];
        b.node = edge.to_node;
        b.position = edge.to;
        b.ends.push_back({e, false, edge.to, 0, 0, 0, {}});
    }
    auto geometry_of = [&](const NodeLayout::End& end) {
        return end_geometry(graph.edges[end.edge], widths[end.edge], end.at_from);
    };
    auto geometry_at = [&](const NodeLayout& node) {
        std::vector<EndGeometry> geo;
        for (const NodeLayout::End& end : node.ends) geo.push_back(geometry_of(end));
        return geo;
    };
    // Counter-clockwise around the node; in a merged junction the ends leave from
    // different nodes, so the angle is taken around the centre to a point well out.
    auto sort_ends = [&](NodeLayout& node) {
        std::vector<std::pair<double, NodeLayout::End>> keyed;
        keyed.reserve(node.ends.size());
        for (const NodeLayout::End& end : node.ends) {
            const EndGeometry g = geometry_of(end);
            const Vec2 far = g.origin - node.position + g.dir * 50.0;
            keyed.emplace_back(std::atan2(far.y, far.x), end);
        }
        std::sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) {
            if (a.first != b.first) return a.first < b.first;
            return a.second.edge != b.second.edge ? a.second.edge < b.second.edge : a.second.at_from < b.second.at_from;
        });
        for (size_t i = 0; i < keyed.size(); ++i) node.ends[i] = std::move(keyed[i].second);
    };
    std::vector<double> from_demand(n, 0), to_demand(n, 0), from_fixed(n, 0), to_fixed(n, 0);
    auto demand_of = [&](const NodeLayout::End& end) -> double& {
        return end.at_from ? from_demand[end.edge] : to_demand[end.edge];
    };
    auto cut_of = [&](const NodeLayout::End& end) -> EdgeEndCut& {
        return end.at_from ? out.from_cut[end.edge] : out.to_cut[end.edge];
    };
    std::map<int64_t, const NodeLayout*> followed_nodes;
    if (follow)
        for (const NodeLayout& f : follow->nodes) followed_nodes[f.node] = &f;

    // Pass 1: order the ends at every node, choose miters, and note how far every joint
    // would like to cut each edge back.
    for (auto& [id, node] : nodes) {
        sort_ends(node);
        const std::vector<EndGeometry> geo = geometry_at(node);
        auto it = followed_nodes.find(id);
        const NodeLayout* followed = it == followed_nodes.end() ? nullptr : it->second;
        const size_t k = node.ends.size();
        if (k == 1) {
            node.kind = JoinKind::End;
            continue;
        }
        if (k == 2 && (!followed || followed->kind == JoinKind::Miter)) {
            EdgeEndCut ca, cb;
            if (miter_cuts(node.position, geo[0], geo[1], miter_limit, followed != nullptr, ca, cb)) {
                node.kind = JoinKind::Miter;
                cut_of(node.ends[0]) = ca;
                cut_of(node.ends[1]) = cb;
                for (int i = 0; i < 2; ++i) {
                    const EdgeEndCut& c = i == 0 ? ca : cb;
                    const NodeLayout::End& end = node.ends[i];
                    (end.at_from ? from_fixed : to_fixed)[end.edge] = std::max({0.0, c.t_left, c.t_right});
                }
                continue;
            }
        }
        node.kind = JoinKind::Joint;
        for (size_t i = 0; i < k; ++i) demand_of(node.ends[i]) = joint_demand(geo, i);
    }

    // Pass 2: junctions closer together than their roads are wide become one joint
    // (osm2streets does the same): the short edges between them are absorbed.
    if (follow) {
        out.absorbed = follow->absorbed;
    } else {
        std::map<int64_t, int64_t> parent;
        std::map<int64_t, std::vector<Vec2>> members;
        std::function<int64_t(int64_t)> root = [&](int64_t v) {
            auto it = parent.find(v);
            if (it == parent.end() || it->second == v) return v;
            return it->second = root(it->second);
        };
        for (uint32_t e = 0; e < n; ++e) {
            const RoadGraphEdge& edge = graph.edges[e];
            if (nodes[edge.from_node].kind != JoinKind::Joint || nodes[edge.to_node].kind != JoinKind::Joint) continue;
            if (from_demand[e] + to_demand[e] <= 0.9 * length(edge.to - edge.from)) continue;
            const int64_t a = root(edge.from_node), b = root(edge.to_node);
            if (a == b) continue;
            std::vector<Vec2> pa = members.count(a) ? members[a] : std::vector<Vec2>{edge.from};
            std::vector<Vec2> pb = members.count(b) ? members[b] : std::vector<Vec2>{edge.to};
            double span = 0;
            for (Vec2 p : pa)
                for (Vec2 q : pb) span = std::max(span, length(p - q));
            if (span > kMaxJunctionSpan) continue;
            parent[a] = parent[b] = std::min(a, b);
            parent[std::max(a, b)] = std::min(a, b);
            pa.insert(pa.end(), pb.begin(), pb.end());
            members[std::min(a, b)] = pa;
        }
        for (uint32_t e = 0; e < n; ++e)
            out.absorbed[e] = root(graph.edges[e].from_node) == root(graph.edges[e].to_node) &&
                              parent.count(graph.edges[e].from_node);
    }
    {
        // Merge the nodes joined by absorbed edges into one node keyed by the smallest id.
        std::map<int64_t, int64_t> parent;
        std::function<int64_t(int64_t)> root = [&](int64_t v) {
            auto it = parent.find(v);
            if (it == parent.end() || it->second == v) return v;
            return it->second = root(it->second);
        };
        for (uint32_t e = 0; e < n; ++e) {
            if (!out.absorbed[e]) continue;
            const int64_t a = root(graph.edges[e].from_node), b = root(graph.edges[e].to_node);
            if (a != b) parent[std::max(a, b)] = std::min(a, b);
        }
        std::map<int64_t, std::vector<int64_t>> clusters;
        for (const auto& [v, p] : parent) clusters[root(v)].push_back(v);
        for (auto& [r, rest] : clusters) {
            NodeLayout merged;
            merged.node = r;
            merged.kind = JoinKind::Joint;
            merged.members = {r};
            merged.members.insert(merged.members.end(), rest.begin(), rest.end());
            std::sort(merged.members.begin(), merged.members.end());
            Vec2 sum;
            for (int64_t m : merged.members) {
                const NodeLayout& node = nodes[m];
                sum = sum + node.position;
                for (const NodeLayout::End& end : node.ends) {
                    if (out.absorbed[end.edge]) continue;
                    merged.ends.push_back(end);
                    (end.at_from ? from_fixed : to_fixed)[end.edge] = 0;
                }
            }
            merged.position = sum * (1.0 / merged.members.size());
            for (int64_t m : merged.members) nodes.erase(m);
            sort_ends(merged);
            const std::vector<EndGeometry> geo = geometry_at(merged);
            for (size_t i = 0; i < merged.ends.size(); ++i) demand_of(merged.ends[i]) = joint_demand(geo, i);
            nodes[r] = std::move(merged);
        }
    }

    // Pass 3: share each edge's length between the joints at its two ends, keeping 10%
    // of it (and whatever a miter at either end needs) for the quad.
    std::vector<double> from_allowed(n), to_allowed(n);
    for (uint32_t e = 0; e < n; ++e) {
        const double len = length(graph.edges[e].to - graph.edges[e].from);
        const double room = std::max(0.0, 0.9 * len - from_fixed[e] - to_fixed[e]);
        const double wanted = from_demand[e] + to_demand[e];
        const double scale = wanted > room ? room / wanted : 1.0;
        from_allowed[e] = from_demand[e] * scale;
        to_allowed[e] = to_demand[e] * scale;
    }

    // With `only`: the accepted nodes, the edges whose quads they need, and every node
    // whose cuts those quads need (both ends of each such edge).
    auto accepts = [](const NodeLayout& node, const std::function<bool(int64_t)>& f) {
        return f(node.node) || std::any_of(node.members.begin(), node.members.end(), f);
    };
    std::vector<bool> quad_wanted(n, !only);
    std::set<int64_t> cut_wanted;
    if (only)
        for (const auto& [id, node] : nodes) {
            if (!accepts(node, only)) continue;
            for (const NodeLayout::End& end : node.ends) {
                quad_wanted[end.edge] = true;
                cut_wanted.insert(graph.edges[end.edge].from_node);
                cut_wanted.insert(graph.edges[end.edge].to_node);
            }
        }
    auto lay_out = [&](const NodeLayout& node) {
        return !only || accepts(node, [&](int64_t v) { return cut_wanted.count(v) > 0; });
    };

    // Pass 4: joint polygons with the shared-out cuts.
    std::map<int64_t, std::vector<Ring>> raw_rings;
    for (auto& [id, node] : nodes) {
        if (node.kind != JoinKind::Joint || node.ends.empty() || !lay_out(node)) continue;
        std::vector<EndGeometry> geo = geometry_at(node);
        for (size_t i = 0; i < geo.size(); ++i) {
            const NodeLayout::End& end = node.ends[i];
            geo[i].max_cut = end.at_from ? from_allowed[end.edge] : to_allowed[end.edge];
            const double len = length(graph.edges[end.edge].to - graph.edges[end.edge].from);
            const double other = end.at_from ? to_allowed[end.edge] + to_fixed[end.edge]
                                             : from_allowed[end.edge] + from_fixed[end.edge];
            geo[i].limit = std::max(geo[i].max_cut, 0.9 * len - other);
        }
        raw_rings[id] = layout_joint(node, geo);
        for (const NodeLayout::End& end : node.ends) cut_of(end) = {end.cut_left, end.cut_right};
    }

    for (uint32_t e = 0; e < n; ++e) {
        if (out.absorbed[e] || !quad_wanted[e]) continue;
        Ring q = quad_for_cuts(graph.edges[e], widths[e], out.from_cut[e], out.to_cut[e]);
        if (quad_is_valid(q)) out.quads[e] = std::move(q);
    }
    for (auto& [id, node] : nodes)
        if (node.kind == JoinKind::Joint && !node.ends.empty() && (!only || accepts(node, only)))
            finish_joint(node, raw_rings[id], out.quads);
    out.nodes.reserve(nodes.size());
    for (auto& [id, node] : nodes) out.nodes.push_back(std::move(node));
    return out;
}

}  // namespace citygen
