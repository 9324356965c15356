// Small geometric rules the road stages share (layout, polygons, sidewalks): one
// definition of each, with its tolerance named.
#pragma once

#include <array>
#include <cstdint>
#include <map>
#include <vector>

#include "common/geometry.h"

namespace citygen {

// Metres: points closer than this are one point.
inline constexpr double kSamePoint = 1e-4;
// Relative: a vertex whose neighbours turn by less than this (times the two edge lengths)
// lies on a straight line.
inline constexpr double kStraightTolerance = 1e-9;
// Radians: a gap this close to a half turn (or wider) has no corner to fill.
inline constexpr double kStraightGap = kPi - 1e-3;

// Intersection p1 + s*d1 = p2 + u*d2; false when the lines are (nearly) parallel.
bool intersect_lines(Vec2 p1, Vec2 d1, Vec2 p2, Vec2 d2, double& s, double& u);

// The angle (0, 2 pi] turned counter-clockwise from direction `a` to direction `b`: the
// gap between two roads leaving a node, measured on the left of `a`.
double gap_angle(Vec2 a, Vec2 b);

// Appends `p` unless it is the same point as the ring's last.
void push_distinct(Ring& ring, Vec2 p);

// What clean_ring removes besides repeated points.
enum class RingCleaning {
    Spikes,               // vertices where the boundary runs out and straight back
    SpikesAndCollinear,   // and vertices on a straight line between their neighbours
};
// `ring` without repeated points (also across its closing edge) and, as asked, without
// spikes or collinear vertices.
Ring clean_ring(const Ring& ring, RingCleaning what);

// Nine points 1 cm beyond the end of convex CCW quad `q` at its `from` end (edge 3) or
// its `to` end (edge 1), evenly spread across it: where a joint should cover the ground.
std::array<Vec2, 9> points_beyond_quad_end(const Ring& q, bool at_from);

// Convex hull (CCW, no collinear points) of a point set.
Ring convex_hull(std::vector<Vec2> points);

// Union-find over OSM node ids: which nodes have been joined into one junction.
class NodeUnionFind {
public:
    int64_t root(int64_t v);
    // Joins the sets of a and b under the smaller root; false when already one set.
    bool join(int64_t a, int64_t b);
    // Whether `v` was ever joined to another node.
    bool joined(int64_t v) const { return parent_.count(v) > 0; }
    // Every joined node by its root, each list ascending.
    std::map<int64_t, std::vector<int64_t>> sets();

private:
    std::map<int64_t, int64_t> parent_;
};

}  // namespace citygen
