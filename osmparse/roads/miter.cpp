// Miter: a degree-2 node where the two quads meet on the line through the intersections
// of their offset lines (osm2streets' degenerate case). A turn too sharp for a miter
// (beyond the miter limit, or cutting too far into an edge) is laid out as a junction.
#include <algorithm>
#include <cmath>

#include "osmparse/roads/layout_state.h"

namespace citygen {

namespace {

constexpr double kStraightCos = 0.99996;  // cos(0.5 deg): closer to straight needs no miter

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

}  // namespace

bool lay_out_miter(LayoutState& state, NodeLayout& node, bool forced) {
    const std::vector<EndGeometry> geo = state.geometry_at(node);
    EdgeEndCut cuts[2];
    if (!miter_cuts(node.position, geo[0], geo[1], state.miter_limit, forced, cuts[0], cuts[1])) return false;
    node.kind = JoinKind::Miter;
    for (int i = 0; i < 2; ++i) {
        const NodeLayout::End& end = node.ends[i];
        state.cut_of(end) = cuts[i];
        // The miter's reach into the edge is not the joint's to share.
        state.fixed.at(end.edge, end.at_from) = std::max({0.0, cuts[i].t_left, cuts[i].t_right});
    }
    return true;
}

}  // namespace citygen
