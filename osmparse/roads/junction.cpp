// Junction: the general case (osm2streets' general case), a node of degree >= 3 or a
// degree-2 turn too sharp for a miter. The ends are sorted by angle and
// the offset lines of neighbours intersected; those corners form the joint polygon, and
// each quad starts where the joint ends. finish_joint.cpp later cuts the quads out of it.
#include <algorithm>
#include <cmath>

#include "osmparse/roads/layout_state.h"

namespace citygen {

namespace {

constexpr double kCrossEps = 1e-4;  // cut segments touching at their ends do not cross

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
        if (gap_angle(gi.dir, gj.dir) >= kStraightGap) continue;
        double s, u;
        if (!intersect_lines(gi.left_at(0), gi.dir, gj.right_at(0), gj.dir, s, u))
            continue;
        demand = std::max(demand, std::min(side == 0 ? s : u, corner_reach(gi, gj)));
    }
    return demand;
}

// What shaping one junction works on; the steps below fill it in order.
struct JunctionWork {
    NodeLayout& node;
    const std::vector<EndGeometry>& geo;
    size_t k;
    std::vector<double> demand_left, demand_right;
    std::vector<bool> cut_short;   // the corner of gap (i, i+1) was not reached
    std::vector<bool> common_cut;  // gap (i, i+1) is closed by one line across both ends
    std::vector<bool> crosses;     // the cuts of ends i and i+1 still cross
    std::vector<Vec2> crossing;
    JunctionWork(NodeLayout& n, const std::vector<EndGeometry>& g)
        : node(n), geo(g), k(n.ends.size()), demand_left(k, 0), demand_right(k, 0), cut_short(k, false),
          common_cut(k, false), crosses(k, false), crossing(k) {}
    bool cuts_cross(size_t i) const;
};

// Step 1: the corner of every gap, where the offset lines of neighbours meet, cut short
// where it lies too far out (near-parallel neighbours, short edges); each end is cut
// square at the furthest corner beside it.
void place_corners(JunctionWork& w) {
    const size_t k = w.k;
    for (size_t i = 0; i < k; ++i) {
        const size_t j = (i + 1) % k;
        const EndGeometry &gi = w.geo[i], &gj = w.geo[j];
        w.node.ends[i].gap_points.clear();
        if (k == 1 || gap_angle(gi.dir, gj.dir) >= kStraightGap) continue;  // open or straight side: a plain bevel
        double s, u;
        if (!intersect_lines(gi.left_at(0), gi.dir, gj.right_at(0), gj.dir, s, u))
            continue;
        const double s_full = s, u_full = u;
        s = std::clamp(s, 0.0, std::min(gi.max_cut, corner_reach(gi, gj)));
        u = std::clamp(u, 0.0, std::min(gj.max_cut, corner_reach(gi, gj)));
        w.cut_short[i] = s < s_full - kSamePoint || u < u_full - kSamePoint;
        w.demand_left[i] = s;
        w.demand_right[j] = u;
        w.node.ends[i].gap_points.push_back(gi.left_at(s));
        w.node.ends[i].gap_points.push_back(gj.right_at(u));
    }
    for (size_t i = 0; i < k; ++i) {
        NodeLayout::End& end = w.node.ends[i];
        end.trim = end.cut_left = end.cut_right = std::max(w.demand_left[i], w.demand_right[i]);
    }
}

bool JunctionWork::cuts_cross(size_t i) const {
    const size_t j = (i + 1) % k;
    const Vec2 ri = geo[i].right_at(node.ends[i].trim), li = geo[i].left_at(node.ends[i].trim);
    const Vec2 rj = geo[j].right_at(node.ends[j].trim), lj = geo[j].left_at(node.ends[j].trim);
    double s, u;
    return intersect_lines(ri, li - ri, rj, lj - rj, s, u) && s > kCrossEps && s < 1 - kCrossEps && u > kCrossEps && u < 1 - kCrossEps;
}

// Step 2: where a corner was cut short the two quads still overlap there, and between
// their square cuts and the joint's chord a sliver would be left uncovered (or the
// cuts even cross). Both are then cut on one common line across the pair,
// perpendicular to the gap's bisector and beyond both square cuts: the joint ends
// on that line, the two quads start on it (and overlap beyond, as the roads do).
void share_common_cuts(JunctionWork& w) {
    const size_t k = w.k;
    NodeLayout& node = w.node;
    const std::vector<EndGeometry>& geo = w.geo;
    for (size_t i = 0; i < k && k > 1; ++i) {
        const size_t j = (i + 1) % k;
        if (!(w.cut_short[i] || w.cuts_cross(i)) || w.common_cut[i] || w.common_cut[j] || (k > 2 && w.cuts_cross(j))) continue;
        // The least each end must keep cut: the corner on its other side (or the line
        // it already shares with its other neighbour).
        const size_t h = (i + k - 1) % k;
        const double least[2] = {w.common_cut[h] ? node.ends[i].trim : w.demand_right[i], w.demand_left[j]};
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
                fits = std::min(cuts[e][0], cuts[e][1]) >= least[e] - kSamePoint &&
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
        w.common_cut[i] = true;
    }
}

// Step 3: any crossing left (a chain of near-parallel roads): the ring takes the four
// cut ends in the order they lie around the node (the two cuts are its diagonals), and
// finish_joint cuts the two quads out of it.
void find_crossings(JunctionWork& w) {
    const size_t k = w.k;
    const std::vector<EndGeometry>& geo = w.geo;
    for (size_t i = 0; i < k && k > 1; ++i) {
        const size_t j = (i + 1) % k;
        // Only a gap under a half turn has a corner to cross at (with two ends, the same
        // two cuts would otherwise cross on both sides).
        if (w.common_cut[i] || cross(geo[i].dir, geo[j].dir) <= 0) continue;
        const Vec2 ri = geo[i].right_at(w.node.ends[i].cut_right), li = geo[i].left_at(w.node.ends[i].cut_left);
        const Vec2 rj = geo[j].right_at(w.node.ends[j].cut_right), lj = geo[j].left_at(w.node.ends[j].cut_left);
        double s, u;
        if (intersect_lines(ri, li - ri, rj, lj - rj, s, u) && s > kCrossEps && s < 1 - kCrossEps && u > kCrossEps && u < 1 - kCrossEps) {
            w.crosses[i] = true;
            w.crossing[i] = ri + (li - ri) * s;
        }
    }
}

// Step 4: the ring through every end's cut and every gap's corner points. With
// `at_crossing`, crossing cuts meet at their crossing point instead (smaller, but it can
// leave a hole beside either quad): the fallback where cutting the quads out of the
// larger ring fails.
Ring joint_ring(const JunctionWork& w, bool at_crossing) {
    const size_t k = w.k;
    const std::vector<EndGeometry>& geo = w.geo;
    Ring ring;
    for (size_t i = 0; i < k; ++i) {
        const NodeLayout::End& end = w.node.ends[i];
        const size_t prev = (i + k - 1) % k;
        if (!w.crosses[prev]) push_distinct(ring, geo[i].right_at(end.cut_right));
        else if (at_crossing) push_distinct(ring, w.crossing[prev]);
        if (w.crosses[i]) {
            if (at_crossing) {
                push_distinct(ring, w.crossing[i]);
            } else {
                push_distinct(ring, geo[(i + 1) % k].right_at(w.node.ends[(i + 1) % k].cut_right));
                push_distinct(ring, geo[i].left_at(end.cut_left));
            }
            continue;
        }
        push_distinct(ring, geo[i].left_at(end.cut_left));
        if (!w.common_cut[i])
            for (Vec2 q : end.gap_points) push_distinct(ring, q);
    }
    return ring;
}

// Each edge's cut at a node and the joint's rings, unfinished: the exact ring, and where
// cuts cross a smaller fallback ring.
std::vector<Ring> layout_joint(NodeLayout& node, const std::vector<EndGeometry>& geo) {
    JunctionWork w(node, geo);
    place_corners(w);
    share_common_cuts(w);
    find_crossings(w);
    for (size_t i = 0; i < w.k; ++i)
        if (w.common_cut[i]) node.ends[i].gap_points.clear();  // the next end starts on the same line
    std::vector<Ring> rings{joint_ring(w, false)};
    if (std::find(w.crosses.begin(), w.crosses.end(), true) != w.crosses.end()) rings.push_back(joint_ring(w, true));
    return rings;
}

}  // namespace

void note_junction_demand(LayoutState& state, NodeLayout& node) {
    node.kind = JoinKind::Joint;
    const std::vector<EndGeometry> geo = state.geometry_at(node);
    for (size_t i = 0; i < node.ends.size(); ++i)
        state.demand.at(node.ends[i].edge, node.ends[i].at_from) = joint_demand(geo, i);
}

void shape_junction(LayoutState& state, NodeLayout& node) {
    std::vector<EndGeometry> geo = state.geometry_at(node);
    for (size_t i = 0; i < geo.size(); ++i) {
        const NodeLayout::End& end = node.ends[i];
        geo[i].max_cut = state.allowed.at(end.edge, end.at_from);
        const double len = state.edge_length(end.edge);
        const double other = state.allowed.at(end.edge, !end.at_from) + state.fixed.at(end.edge, !end.at_from);
        geo[i].limit = std::max(geo[i].max_cut, kJointsTake * len - other);
    }
    state.raw_rings[node.node] = layout_joint(node, geo);
    for (const NodeLayout::End& end : node.ends) state.cut_of(end) = {end.cut_left, end.cut_right};
}

}  // namespace citygen
