#include "osmparse/polygons/clean_footprint.h"

#include "osmparse/polygons/cgal_footprint.h"
#include "osmparse/polygons/exact_predicates.h"
#include "osmparse/polygons/ring_is_simple.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

namespace citygen {

namespace {

// Angle in radians between two directions, in [0, pi]; pi for a zero vector.
double angle_between(Vec2 a, Vec2 b) {
    if (length(a) == 0 || length(b) == 0) return kPi;
    return std::atan2(std::fabs(cross(a, b)), dot(a, b));
}

// How deep a point lies behind a line (interior_point's choice of a vertex, not a decision).
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
            if (edge.overlaps(other) && exact_segments_touch(p, q, r, s)) return false;
        }
    }
    return true;
}

// `inner` lies strictly inside `outer`: boundaries apart and a point of inner inside outer.
bool ring_strictly_inside(const Ring& inner, const Ring& outer) {
    return rings_disjoint_boundaries(inner, outer) && exact_point_in_ring(inner[0], outer);
}

Ring oriented(Ring ring, bool counter_clockwise) {
    if ((ring_orientation_exact(ring) > 0) != counter_clockwise) std::reverse(ring.begin(), ring.end());
    return ring;
}

enum class RingOutcome { Clean, Repaired, Degenerate, Unrepairable };

// One simple piece of a ring, before and after merging small turns.
struct Piece {
    Ring unsimplified;
    Ring ring;
};

// merge_small_turns, kept only if the result is simple. The hand-written merge stays for the
// common case, a ring on its own: CGAL's simplify_keeping_topology took 3-14x its time on
// Kaiserslautern's footprints and 70-120x on Monaco's (tests/bench/footprint_bench, two runs),
// and its greedy order keeps other vertices in 5% of the rings, which would change most
// scenes. Where rings must be simplified together (pieces of a split ring, a hole the merged
// outline would cross) CGAL's is used instead.
Ring simplified_alone(const Ring& ring, double simplify_angle_deg) {
    Ring merged = remove_repeated_and_collinear(merge_small_turns(ring, simplify_angle_deg));
    return merged.size() >= 3 && ring_is_simple(merged) ? merged : ring;
}

// The rings simplified together, so none crosses itself or another (CGAL), each cleaned of
// repeated and collinear points as simplified_alone does; the unsimplified rings where
// that leaves one that is not simple.
std::vector<Ring> simplified_together(const std::vector<Ring>& rings, double simplify_angle_deg) {
    std::vector<Ring> out = simplify_keeping_topology(rings, simplify_angle_deg);
    for (size_t i = 0; i < out.size(); ++i) {
        out[i] = remove_repeated_and_collinear(out[i]);
        if (out[i].size() < 3 || !ring_is_simple(out[i])) return rings;
    }
    return out;
}

// rings[0] is an outline, the others its holes: each hole strictly inside it and apart from
// the other holes.
bool holes_inside_and_apart(const std::vector<Ring>& rings) {
    for (size_t i = 1; i < rings.size(); ++i) {
        if (!ring_strictly_inside(rings[i], rings[0])) return false;
        for (size_t j = 1; j < i; ++j)
            if (!rings_disjoint_boundaries(rings[i], rings[j]) || exact_point_in_ring(rings[i][0], rings[j]) ||
                exact_point_in_ring(rings[j][0], rings[i]))
                return false;
    }
    return true;
}

// Steps 1-3 for one ring: simple pieces, orientation not yet fixed.
std::vector<Piece> clean_ring(const Ring& input, double simplify_angle_deg, RingOutcome& outcome) {
    const Ring ring = remove_repeated_and_collinear(input);
    if (ring.size() < 3) {
        outcome = RingOutcome::Degenerate;
        return {};
    }
    if (ring_is_simple(ring)) {
        outcome = RingOutcome::Clean;
        return {{ring, simplified_alone(ring, simplify_angle_deg)}};
    }
    // Pieces of a split ring touch where the ring crossed itself: simplifying them one by one
    // could make them overlap there.
    const std::vector<Ring> pieces = split_self_intersections(ring);
    const std::vector<Ring> simplified = simplified_together(pieces, simplify_angle_deg);
    outcome = pieces.empty() ? RingOutcome::Unrepairable : RingOutcome::Repaired;
    std::vector<Piece> out;
    for (size_t i = 0; i < pieces.size(); ++i) out.push_back({pieces[i], simplified[i]});
    return out;
}

void report_outcome(RingOutcome outcome, ReportKind kind, ParseReport& report) {
    if (outcome == RingOutcome::Degenerate) report.dropped(kind, ReportReason::Degenerate);
    if (outcome == RingOutcome::Unrepairable) report.dropped(kind, ReportReason::Unrepairable);
    if (outcome == RingOutcome::Repaired) report.note(kind, ReportReason::Repaired);
}

enum class HoleFate { Kept, BelowMinArea, Outside, Overlaps };

struct HoleAssignment {
    std::vector<HoleFate> fate;
    std::vector<int> home;  // index into the outers, -1 for none
};

// Each hole goes to the (last) outer it lies strictly inside, unless it is a sliver or meets
// a hole already accepted there; on the simplified rings or on the unsimplified ones.
HoleAssignment assign_holes(const std::vector<Piece>& holes, const std::vector<Piece>& outers,
                            bool unsimplified, double min_area) {
    auto ring_of = [&](const Piece& piece) -> const Ring& { return unsimplified ? piece.unsimplified : piece.ring; };
    HoleAssignment out{std::vector<HoleFate>(holes.size(), HoleFate::Kept), std::vector<int>(holes.size(), -1)};
    std::vector<std::vector<const Ring*>> accepted(outers.size());
    for (size_t i = 0; i < holes.size(); ++i) {
        const Ring& hole = ring_of(holes[i]);
        if (std::fabs(signed_area(holes[i].ring)) < min_area) {
            out.fate[i] = HoleFate::BelowMinArea;
            continue;
        }
        int home = -1;
        for (size_t p = 0; p < outers.size(); ++p)
            if (ring_strictly_inside(hole, ring_of(outers[p]))) home = static_cast<int>(p);
        if (home < 0) {
            out.fate[i] = HoleFate::Outside;
            continue;
        }
        bool overlaps = false;
        for (const Ring* other : accepted[home])
            overlaps |= !rings_disjoint_boundaries(hole, *other) || exact_point_in_ring(hole[0], *other) ||
                        exact_point_in_ring((*other)[0], hole);
        if (overlaps) {
            out.fate[i] = HoleFate::Overlaps;
            continue;
        }
        out.home[i] = home;
        accepted[home].push_back(&hole);
    }
    return out;
}

// CGAL's check for an outline alone; with holes, the same rules on the exact predicates (CGAL's
// general check builds exact constructions and took 10x the land-cover stage on Malta's).
bool polygon_is_valid(const Footprint& f) {
    if (f.holes.empty()) return polygon_is_valid_exact(f.outer, {});
    std::vector<Ring> rings{f.outer};
    if (!ring_is_simple(f.outer) || ring_orientation_exact(f.outer) <= 0) return false;
    for (const Ring& h : f.holes) {
        if (!ring_is_simple(h) || ring_orientation_exact(h) >= 0) return false;
        rings.push_back(h);
    }
    return holes_inside_and_apart(rings);
}

// The polygons worth storing: not slivers, and valid by CGAL's check of the stage's output.
std::vector<Footprint> keep_valid(std::vector<Footprint> polygons, double min_area, ParseReport& report,
                                  ReportKind kind, ReportKind hole_kind) {
    std::vector<Footprint> kept;
    for (Footprint& f : polygons) {
        double area = signed_area(f.outer);
        for (const Ring& h : f.holes) area += signed_area(h);  // holes are CW: negative
        if (area < min_area) {
            report.dropped(kind, ReportReason::SliverBelowMinArea);
            continue;
        }
        // The stage's output checked again: a polygon that fails is counted and never stored.
        if (!polygon_is_valid(f)) {
            report.dropped(kind, ReportReason::InvalidAtOutput);
            continue;
        }
        report.kept(hole_kind, static_cast<int64_t>(f.holes.size()));
        kept.push_back(std::move(f));
    }
    return kept;
}

}  // namespace

Ring remove_repeated_and_collinear(Ring ring, double tolerance) {
    for (bool changed = true; changed;) {
        changed = false;
        // Repeated vertices, including a closing copy of the first one.
        Ring kept;
        kept.reserve(ring.size());
        for (Vec2 p : ring)
            if (kept.empty() || !exact_within_distance(p, kept.back(), tolerance)) kept.push_back(p);
        while (kept.size() >= 2 && exact_within_distance(kept.back(), kept.front(), tolerance)) kept.pop_back();
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
            if (!neighbour_dropped && exact_near_line(ring[i], ring[(i + n - 1) % n], ring[(i + 1) % n], tolerance)) {
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
    // The crossings come from CGAL's arrangement (exact intersection points); the loops are
    // rounded to float there, so they are cleaned and checked again here.
    std::vector<Ring> pieces;
    for (Ring& loop : split_at_crossings_exact(ring)) {
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
    const int sign = exact_orientation(a, b, c) > 0 ? 1 : -1;
    size_t deepest = n;
    double best = -1;
    for (size_t i = 0; i < n; ++i) {
        if (i == v || i == (v + 1) % n || i == (v + n - 1) % n) continue;
        const Vec2 p = ring[i];
        const bool inside = sign * exact_orientation(a, b, p) >= 0 && sign * exact_orientation(b, c, p) >= 0 &&
                            sign * exact_orientation(c, a, p) >= 0;
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

// Where simplifying each ring on its own cost a polygon a hole, its holes assigned again on the
// unsimplified rings, if that keeps more of them; true for the polygons whose rings are then
// simplified together.
std::vector<bool> assign_lost_holes_again(const std::vector<Piece>& hole_candidates, const std::vector<Piece>& outers,
                                          double min_area, HoleAssignment& assignment) {
    std::vector<bool> together(outers.size(), false);
    for (size_t p = 0; p < outers.size(); ++p) {
        std::vector<Piece> mine;  // the holes that could be this polygon's, in order
        std::vector<size_t> index;
        bool lost_any = false;
        for (size_t i = 0; i < hole_candidates.size(); ++i) {
            const HoleFate fate = assignment.fate[i];
            const bool lost_to_simplification =
                (fate == HoleFate::Outside || fate == HoleFate::Overlaps) &&
                ring_strictly_inside(hole_candidates[i].unsimplified, outers[p].unsimplified);
            lost_any |= lost_to_simplification;
            if (assignment.home[i] == static_cast<int>(p) || lost_to_simplification) {
                mine.push_back(hole_candidates[i]);
                index.push_back(i);
            }
        }
        if (!lost_any) continue;  // the common case: nothing to win
        const HoleAssignment again = assign_holes(mine, {outers[p]}, true, min_area);
        size_t kept_before = 0, kept_again = 0;
        for (size_t k = 0; k < mine.size(); ++k) {
            kept_before += assignment.fate[index[k]] == HoleFate::Kept;
            kept_again += again.fate[k] == HoleFate::Kept;
        }
        if (kept_again <= kept_before) continue;
        together[p] = true;
        for (size_t k = 0; k < mine.size(); ++k) {
            assignment.fate[index[k]] = again.fate[k];
            assignment.home[index[k]] = again.fate[k] == HoleFate::Kept ? static_cast<int>(p) : -1;
        }
    }
    return together;
}

// The polygons: each outline with the holes assigned to it, oriented.
std::vector<Footprint> assemble_polygons(const std::vector<Piece>& outers, const std::vector<Piece>& hole_candidates,
                                         const HoleAssignment& assignment, const std::vector<bool>& together,
                                         double simplify_angle_deg) {
    std::vector<Footprint> polygons;
    for (size_t p = 0; p < outers.size(); ++p) {
        std::vector<Ring> rings{together[p] ? outers[p].unsimplified : outers[p].ring};
        for (size_t i = 0; i < hole_candidates.size(); ++i)
            if (assignment.home[i] == static_cast<int>(p))
                rings.push_back(together[p] ? hole_candidates[i].unsimplified : hole_candidates[i].ring);
        if (together[p]) {
            // CGAL keeps the rings apart, but the 1 cm clean-up after it may drop an outline
            // vertex a hole was kept clear of: then the unsimplified rings.
            std::vector<Ring> simplified = simplified_together(rings, simplify_angle_deg);
            if (holes_inside_and_apart(simplified)) rings = std::move(simplified);
        }
        Footprint f{oriented(std::move(rings[0]), true), {}};
        for (size_t k = 1; k < rings.size(); ++k) f.holes.push_back(oriented(std::move(rings[k]), false));
        polygons.push_back(std::move(f));
    }
    return polygons;
}

ReportKind holes_row(ReportKind kind) {
    switch (kind) {
        case ReportKind::Buildings:
        case ReportKind::BuildingParts: return ReportKind::BuildingHoles;
        case ReportKind::LandCoverAreas: return ReportKind::LandCoverAreaHoles;
        case ReportKind::SeaPolygons: return ReportKind::SeaPolygonHoles;
        case ReportKind::CoastlineIslands: return ReportKind::CoastlineIslandHoles;
        default: throw std::invalid_argument(std::string("no holes row for ") + text_of(kind));
    }
}

std::vector<Footprint> clean_footprint(const Ring& outer, const std::vector<Ring>& holes,
                                       const BuildingParams& params, ParseReport& report,
                                       ReportKind kind) {
    const ReportKind hole_kind = holes_row(kind);
    RingOutcome outcome = RingOutcome::Clean;
    std::vector<Piece> pieces = clean_ring(outer, params.simplify_angle_deg, outcome);
    report_outcome(outcome, kind, report);

    // Pieces of a split outline: biggest first; a piece inside another is its hole.
    std::sort(pieces.begin(), pieces.end(), [](const Piece& x, const Piece& y) {
        return std::fabs(signed_area(x.ring)) > std::fabs(signed_area(y.ring));
    });
    std::vector<Piece> outers, hole_candidates;
    for (Piece& piece : pieces) {
        bool nested = false;
        for (const Piece& o : outers) nested |= exact_point_in_ring(interior_point(piece.ring), o.ring);
        (nested ? hole_candidates : outers).push_back(std::move(piece));
    }
    for (const Ring& hole : holes) {
        report.read(hole_kind);
        RingOutcome hole_outcome = RingOutcome::Clean;
        std::vector<Piece> hole_pieces = clean_ring(hole, params.simplify_angle_deg, hole_outcome);
        report_outcome(hole_outcome, hole_kind, report);
        for (Piece& piece : hole_pieces) hole_candidates.push_back(std::move(piece));
    }

    // Holes go where the simplified rings say. Simplifying each ring on its own can make a
    // hole meet its outline or another hole that the map kept apart: a polygon where that
    // cost a hole assigns its holes again on the unsimplified rings, then simplifies all its
    // rings together (CGAL), which keeps them apart.
    HoleAssignment assignment = assign_holes(hole_candidates, outers, false, params.min_area);
    const std::vector<bool> together = assign_lost_holes_again(hole_candidates, outers, params.min_area, assignment);
    std::vector<Footprint> polygons =
        assemble_polygons(outers, hole_candidates, assignment, together, params.simplify_angle_deg);
    for (HoleFate fate : assignment.fate) {
        if (fate == HoleFate::BelowMinArea) report.dropped(hole_kind, ReportReason::HoleBelowMinArea);
        if (fate == HoleFate::Outside) report.dropped(hole_kind, ReportReason::HoleOutside);
        if (fate == HoleFate::Overlaps) report.dropped(hole_kind, ReportReason::HoleOverlaps);
    }

    return keep_valid(std::move(polygons), params.min_area, report, kind, hole_kind);
}

}  // namespace citygen
