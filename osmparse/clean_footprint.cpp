#include "clean_footprint.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>

namespace citygen {

namespace {


// Angle in radians between two directions, in [0, pi]; pi for a zero vector.
double angle_between(Vec2 a, Vec2 b) {
    if (length(a) == 0 || length(b) == 0) return kPi;
    return std::atan2(std::fabs(cross(a, b)), dot(a, b));
}

double distance_to_line(Vec2 p, Vec2 a, Vec2 b) {
    const double len = length(b - a);
    return len == 0 ? length(p - a) : std::fabs(cross(b - a, p - a)) / len;
}

// True when no edge of `a` touches an edge of `b`.
bool rings_disjoint_boundaries(const Ring& a, const Ring& b) {
    if (!bounds_of(a).overlaps(bounds_of(b))) return true;
    for (size_t i = 0; i < a.size(); ++i) {
        const Vec2 p = a[i], q = a[(i + 1) % a.size()];
        Box2 edge;
        edge.extend(p);
        edge.extend(q);
        for (size_t j = 0; j < b.size(); ++j) {
            const Vec2 r = b[j], s = b[(j + 1) % b.size()];
            Box2 other;
            other.extend(r);
            other.extend(s);
            if (edge.overlaps(other) && segments_intersect(p, q, r, s)) return false;
        }
    }
    return true;
}

// `inner` lies strictly inside `outer`: boundaries apart and a point of inner inside outer.
bool ring_strictly_inside(const Ring& inner, const Ring& outer) {
    return rings_disjoint_boundaries(inner, outer) && point_in_ring(inner[0], outer);
}

Ring oriented(Ring ring, bool counter_clockwise) {
    if ((signed_area(ring) > 0) != counter_clockwise) std::reverse(ring.begin(), ring.end());
    return ring;
}

enum class RingOutcome { Clean, Repaired, Degenerate, Unrepairable };

// Steps 1-3 for one ring: simple pieces, orientation not yet fixed.
std::vector<Ring> clean_ring(const Ring& input, double simplify_angle_deg, RingOutcome& outcome) {
    const Ring ring = remove_repeated_and_collinear(input);
    if (ring.size() < 3) {
        outcome = RingOutcome::Degenerate;
        return {};
    }
    auto simplified = [&](const Ring& r) {
        Ring merged = remove_repeated_and_collinear(merge_small_turns(r, simplify_angle_deg));
        return merged.size() >= 3 && ring_is_simple(merged) ? merged : r;
    };
    if (ring_is_simple(ring)) {
        outcome = RingOutcome::Clean;
        return {simplified(ring)};
    }
    std::vector<Ring> pieces = split_self_intersections(ring);
    for (Ring& piece : pieces) piece = simplified(piece);
    outcome = pieces.empty() ? RingOutcome::Unrepairable : RingOutcome::Repaired;
    return pieces;
}

}  // namespace

Ring remove_repeated_and_collinear(Ring ring, double tolerance) {
    for (bool changed = true; changed;) {
        changed = false;
        // Repeated vertices, including a closing copy of the first one.
        Ring kept;
        kept.reserve(ring.size());
        for (Vec2 p : ring)
            if (kept.empty() || length(p - kept.back()) > tolerance) kept.push_back(p);
        while (kept.size() >= 2 && length(kept.back() - kept.front()) <= tolerance) kept.pop_back();
        changed |= kept.size() != ring.size();
        ring.swap(kept);
        if (ring.size() < 3) break;
        // Collinear vertices and spikes (a vertex on the line through its neighbours).
        // Never two neighbours in one pass, so each test sees the final neighbours.
        const size_t n = ring.size();
        std::vector<bool> drop(n, false);
        size_t removed = 0;
        for (size_t i = 0; i < n; ++i) {
            const bool neighbour_dropped = (i > 0 && drop[i - 1]) || (i == n - 1 && drop[0]);
            if (!neighbour_dropped && distance_to_line(ring[i], ring[(i + n - 1) % n], ring[(i + 1) % n]) <= tolerance) {
                drop[i] = true;
                ++removed;
            }
        }
        kept.clear();
        for (size_t i = 0; i < n; ++i)
            if (!drop[i]) kept.push_back(ring[i]);
        changed |= removed > 0;
        ring.swap(kept);
        if (ring.size() < 3) break;
    }
    if (ring.size() < 3) ring.clear();
    return ring;
}

Ring merge_small_turns(const Ring& ring, double angle_deg) {
    const size_t n = ring.size();
    const double max_angle = angle_deg * kPi / 180;
    if (n < 4 || max_angle <= 0) return ring;
    // Start at the sharpest corner: it is kept whatever happens, so the result does not
    // depend on where the ring happened to start.
    size_t start = 0;
    double sharpest = -1;
    for (size_t i = 0; i < n; ++i) {
        const double turn = angle_between(ring[i] - ring[(i + n - 1) % n], ring[(i + 1) % n] - ring[i]);
        if (turn > sharpest) {
            sharpest = turn;
            start = i;
        }
    }
    auto at = [&](size_t k) { return ring[(start + k) % n]; };
    // Grow a run of edges from the anchor while the directions of all its edges stay
    // within max_angle of each other; the run becomes one edge. Comparing the whole run,
    // not just neighbours, means a gentle curve is never flattened into one straight edge.
    Ring out{at(0)};
    size_t anchor = 0;
    double lowest = 0, highest = 0;  // directions relative to the run's first edge
    for (size_t k = 1; k < n; ++k) {
        const Vec2 first = at(anchor + 1) - at(anchor), edge = at(k + 1) - at(k);
        const double direction = std::atan2(cross(first, edge), dot(first, edge));
        const double new_lowest = std::min(lowest, direction), new_highest = std::max(highest, direction);
        if (new_highest - new_lowest < max_angle) {
            lowest = new_lowest;
            highest = new_highest;
            continue;
        }
        out.push_back(at(k));  // a corner: start a new run here
        anchor = k;
        lowest = highest = 0;
    }
    return out;
}

std::vector<Ring> split_self_intersections(const Ring& ring) {
    const size_t n = ring.size();
    if (n < 3) return {};
    // 1. Every point where two non-adjacent edges meet becomes a vertex of both edges.
    std::vector<std::vector<std::pair<double, Vec2>>> cuts(n);
    auto param_on = [](Vec2 p, Vec2 a, Vec2 b) { return dot(p - a, b - a) / dot(b - a, b - a); };
    for (size_t i = 0; i < n; ++i) {
        const Vec2 a = ring[i], b = ring[(i + 1) % n];
        for (size_t j = i + 1; j < n; ++j) {
            if (j == i + 1 || (i == 0 && j == n - 1)) continue;
            const Vec2 c = ring[j], d = ring[(j + 1) % n];
            if (!segments_intersect(a, b, c, d)) continue;
            const double den = cross(b - a, d - c);
            if (den != 0) {
                const double t = cross(c - a, d - c) / den;
                Vec2 p = round_to_stored_precision(a + (b - a) * t);
                for (Vec2 end : {a, b, c, d})  // a touch at a vertex stays that vertex
                    if (length(p - end) <= kFootprintTolerance) p = end;
                cuts[i].push_back({param_on(p, a, b), p});
                cuts[j].push_back({param_on(p, c, d), p});
            } else {  // collinear overlap: the ends of each lying on the other
                for (Vec2 e : {c, d})
                    if (segments_intersect(a, b, e, e)) cuts[i].push_back({param_on(e, a, b), e});
                for (Vec2 e : {a, b})
                    if (segments_intersect(c, d, e, e)) cuts[j].push_back({param_on(e, c, d), e});
            }
        }
    }
    Ring walk;
    for (size_t i = 0; i < n; ++i) {
        walk.push_back(ring[i]);
        std::sort(cuts[i].begin(), cuts[i].end(),
                  [](const auto& x, const auto& y) { return x.first < y.first; });
        for (const auto& [t, p] : cuts[i])
            if (p != walk.back() && p != ring[(i + 1) % n]) walk.push_back(p);
    }
    // 2. Walk the ring; whenever it comes back to a point already on the path, the
    //    stretch since then is a closed loop of its own: cut it off.
    std::vector<Ring> loops;
    Ring path;
    std::map<std::pair<double, double>, size_t> position;
    for (Vec2 p : walk) {
        auto it = position.find({p.x, p.y});
        if (it == position.end()) {
            position[{p.x, p.y}] = path.size();
            path.push_back(p);
            continue;
        }
        const size_t k = it->second;
        loops.emplace_back(path.begin() + static_cast<long>(k), path.end());
        for (size_t m = k + 1; m < path.size(); ++m) position.erase({path[m].x, path[m].y});
        path.resize(k + 1);
    }
    loops.push_back(path);
    // 3. Keep the loops that are proper simple rings.
    std::vector<Ring> pieces;
    for (Ring& loop : loops) {
        loop = remove_repeated_and_collinear(loop);
        if (loop.size() >= 3 && ring_is_simple(loop)) pieces.push_back(std::move(loop));
    }
    return pieces;
}

Vec2 interior_point(const Ring& ring) {
    // The lowest-leftmost vertex v is convex. If the triangle (prev, v, next) holds no
    // other vertex its centroid is inside; otherwise the midpoint between v and the
    // vertex in the triangle farthest from the line prev-next is (O'Rourke).
    const size_t n = ring.size();
    size_t v = 0;
    for (size_t i = 1; i < n; ++i)
        if (ring[i].x < ring[v].x || (ring[i].x == ring[v].x && ring[i].y < ring[v].y)) v = i;
    const Vec2 a = ring[(v + n - 1) % n], b = ring[v], c = ring[(v + 1) % n];
    const double sign = cross(b - a, c - b) > 0 ? 1 : -1;
    size_t deepest = n;
    double best = -1;
    for (size_t i = 0; i < n; ++i) {
        if (i == v || i == (v + 1) % n || i == (v + n - 1) % n) continue;
        const Vec2 p = ring[i];
        const bool inside = sign * cross(b - a, p - a) >= 0 && sign * cross(c - b, p - b) >= 0 &&
                            sign * cross(a - c, p - c) >= 0;
        if (!inside) continue;
        const double depth = distance_to_line(p, a, c);
        if (depth > best) {
            best = depth;
            deepest = i;
        }
    }
    if (deepest == n) return (a + b + c) * (1.0 / 3);
    return (b + ring[deepest]) * 0.5;
}

std::vector<Footprint> clean_footprint(const Ring& outer, const std::vector<Ring>& holes,
                                       const BuildingParams& params, ParseReport& report,
                                       const std::string& kind) {
    // Buildings count their holes under "building holes" (as they always did), others under "<kind> holes".
    const std::string hole_kind = kind.rfind("building", 0) == 0 ? std::string("building holes") : kind + " (holes)";
    RingOutcome outcome = RingOutcome::Clean;
    std::vector<Ring> pieces = clean_ring(outer, params.simplify_angle_deg, outcome);
    if (outcome == RingOutcome::Degenerate) report.dropped(kind, "degenerate (fewer than 3 distinct points)");
    if (outcome == RingOutcome::Unrepairable) report.dropped(kind, "self-intersecting, could not repair");
    if (outcome == RingOutcome::Repaired) report.note(kind, "self-intersection repaired by splitting");

    // Pieces of a split outline: biggest first; a piece inside another is its hole.
    std::sort(pieces.begin(), pieces.end(), [](const Ring& x, const Ring& y) {
        return std::fabs(signed_area(x)) > std::fabs(signed_area(y));
    });
    std::vector<Footprint> polygons;
    std::vector<Ring> hole_candidates;
    for (Ring& piece : pieces) {
        bool nested = false;
        for (const Footprint& f : polygons) nested |= point_in_ring(interior_point(piece), f.outer);
        if (nested) hole_candidates.push_back(std::move(piece));
        else polygons.push_back({oriented(std::move(piece), true), {}});
    }
    for (const Ring& hole : holes) {
        report.read(hole_kind);
        RingOutcome hole_outcome = RingOutcome::Clean;
        std::vector<Ring> hole_pieces = clean_ring(hole, params.simplify_angle_deg, hole_outcome);
        if (hole_outcome == RingOutcome::Degenerate) report.dropped(hole_kind, "degenerate (fewer than 3 distinct points)");
        if (hole_outcome == RingOutcome::Unrepairable) report.dropped(hole_kind, "self-intersecting, could not repair");
        if (hole_outcome == RingOutcome::Repaired) report.note(hole_kind, "self-intersection repaired by splitting");
        for (Ring& piece : hole_pieces) hole_candidates.push_back(std::move(piece));
    }

    // Each hole goes to the polygon it lies strictly inside, unless it is a sliver or
    // meets a hole already accepted there.
    for (Ring& hole : hole_candidates) {
        if (std::fabs(signed_area(hole)) < params.min_area) {
            report.dropped(hole_kind, "below min area");
            continue;
        }
        Footprint* home = nullptr;
        for (Footprint& f : polygons)
            if (ring_strictly_inside(hole, f.outer)) home = &f;
        if (!home) {
            report.dropped(hole_kind, "outside or touching the outline");
            continue;
        }
        bool overlaps = false;
        for (const Ring& other : home->holes)
            overlaps |= !rings_disjoint_boundaries(hole, other) || point_in_ring(hole[0], other) ||
                        point_in_ring(other[0], hole);
        if (overlaps) {
            report.dropped(hole_kind, "overlaps another hole");
            continue;
        }
        home->holes.push_back(oriented(std::move(hole), false));
    }

    std::vector<Footprint> kept;
    for (Footprint& f : polygons) {
        double area = signed_area(f.outer);
        for (const Ring& h : f.holes) area += signed_area(h);  // holes are CW: negative
        if (area < params.min_area) {
            report.dropped(kind, "sliver below min area");
            continue;
        }
        report.kept(hole_kind, static_cast<int64_t>(f.holes.size()));
        kept.push_back(std::move(f));
    }
    return kept;
}

}  // namespace citygen
