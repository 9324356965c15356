// Finishing joints against their quads: the last pass of the layout, once every quad
// is known (finish_joint below).
#include <algorithm>
#include <cmath>

#include "osmparse/polygons/polygon_overlap.h"
#include "osmparse/polygons/ring_is_simple.h"
#include "osmparse/roads/layout_state.h"

namespace citygen {

namespace {

constexpr double kMinJointArea = 1e-3;  // square metres

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

}  // namespace

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
            cut = clean_ring(cut, RingCleaning::Spikes);
            if (valid(cut)) ring = std::move(cut);
            else overlap += clipped_area(ring, q);
        }
        return ring;
    };
    // Holes left beside a quad: of the points just beyond its end, those neither in the
    // joint nor in another quad of the node.
    auto holes = [&](const Ring& joint) {
        int count = 0;
        for (const NodeLayout::End& end : node.ends) {
            const Ring& q = quads[end.edge];
            if (q.empty()) continue;
            for (Vec2 p : points_beyond_quad_end(q, end.at_from)) {
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
    const Ring ring = clean_ring(raw_rings[0], RingCleaning::Spikes);
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
        if (consider(clean_ring(raw_rings[r], RingCleaning::Spikes), false, false)) return;
    Ring star = ring;
    std::sort(star.begin(), star.end(), [&](Vec2 a, Vec2 b) {
        return std::atan2(a.y - node.position.y, a.x - node.position.x) <
               std::atan2(b.y - node.position.y, b.x - node.position.x);
    });
    if (consider(star, false, true)) return;
    consider(convex_hull(ring), false, true);
}

}  // namespace citygen
