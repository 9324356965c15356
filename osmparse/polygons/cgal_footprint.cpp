#include "osmparse/polygons/cgal_footprint.h"

#include <CGAL/Arr_curve_data_traits_2.h>
#include <CGAL/Arr_segment_traits_2.h>
#include <CGAL/Arrangement_2.h>
#include <CGAL/Boolean_set_operations_2.h>
#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Constrained_triangulation_plus_2.h>
#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_2_algorithms.h>
#include <CGAL/Polygon_with_holes_2.h>
#include <CGAL/Polyline_simplification_2/Stop_above_cost_threshold.h>
#include <CGAL/Polyline_simplification_2/simplify.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iterator>
#include <list>
#include <unordered_map>

#include "osmparse/polygons/clean_footprint.h"  // round_to_float

namespace citygen {

namespace {

using Inexact = CGAL::Exact_predicates_inexact_constructions_kernel;  // predicates exact
using Exact = CGAL::Exact_predicates_exact_constructions_kernel;      // new points exact too

template <typename Kernel>
std::vector<typename Kernel::Point_2> points_of(const Ring& ring) {
    std::vector<typename Kernel::Point_2> points;
    points.reserve(ring.size());
    for (Vec2 p : ring) points.emplace_back(p.x, p.y);
    return points;
}

// ---- splitting: an arrangement whose edges count how many ring segments run along them ----

using SegmentTraits = CGAL::Arr_segment_traits_2<Exact>;
// Overlapping segments merge into one edge whose count is the sum of theirs.
using CountedSegmentTraits = CGAL::Arr_curve_data_traits_2<SegmentTraits, unsigned, std::plus<unsigned>>;
using Arrangement = CGAL::Arrangement_2<CountedSegmentTraits>;

// The loops of one boundary cycle of a face, cut wherever the cycle comes back to a vertex it
// already passed (a pinch, or the two sides of an edge with the same face on both).
void add_loops(Arrangement::Ccb_halfedge_const_circulator first, std::vector<Ring>& loops) {
    std::vector<Arrangement::Vertex_const_handle> path;
    std::unordered_map<const void*, size_t> position;
    auto emit = [&](size_t from) {
        Ring loop;
        for (size_t k = from; k < path.size(); ++k) {
            const Exact::Point_2& p = path[k]->point();
            loop.push_back({round_to_float(CGAL::to_double(p.x())), round_to_float(CGAL::to_double(p.y()))});
        }
        if (loop.size() >= 3) loops.push_back(std::move(loop));
    };
    auto h = first;
    do {
        const auto v = h->source();
        const auto it = position.find(&*v);
        if (it == position.end()) {
            position[&*v] = path.size();
            path.push_back(v);
            continue;
        }
        const size_t k = it->second;
        emit(k);
        for (size_t m = k + 1; m < path.size(); ++m) position.erase(&*path[m]);
        path.resize(k + 1);
    } while (++h != first);
    emit(0);
}

// ---- simplification ----

namespace PS = CGAL::Polyline_simplification_2;
using SimplifyTriangulation = CGAL::Constrained_triangulation_plus_2<CGAL::Constrained_Delaunay_triangulation_2<
    Inexact,
    CGAL::Triangulation_data_structure_2<PS::Vertex_base_2<Inexact>, CGAL::Constrained_triangulation_face_base_2<Inexact>>,
    CGAL::Exact_predicates_tag>>;

double angle_between(double ax, double ay, double bx, double by) {
    return std::atan2(std::fabs(ax * by - ay * bx), ax * bx + ay * by);
}

// The cost of removing vertex q (between p and r): the largest angle between the new edge
// p-r and any original edge it replaces. The same rule as merge_small_turns.
struct DirectionSpreadCost {
    template <class CDT>
    boost::optional<double> operator()(
        const CGAL::Constrained_triangulation_plus_2<CDT>&,
        typename CGAL::Constrained_triangulation_plus_2<CDT>::Vertices_in_constraint_iterator q) const {
        using Points = typename CGAL::Constrained_triangulation_plus_2<CDT>::Points_in_constraint_iterator;
        // Not std::prev: these iterators call themselves forward-only, and std::prev on one
        // steps forward for ever.
        auto p = q, r = q;
        --p;
        ++r;
        const auto& a = (*p)->point();
        const auto& b = (*r)->point();
        const double dx = b.x() - a.x(), dy = b.y() - a.y();
        if (dx == 0 && dy == 0) return kPi;
        double worst = 0;
        Points point(p);
        const Points last(r);
        auto previous = *point;
        do {
            ++point;
            const auto current = *point;
            worst = std::max(worst, angle_between(dx, dy, current.x() - previous.x(), current.y() - previous.y()));
            previous = current;
        } while (point != last);
        return worst;
    }
};

// The ring turned to start at its sharpest corner (a closed constraint's first vertex stays).
Ring starting_at_sharpest_corner(const Ring& ring) {
    const size_t n = ring.size();
    size_t start = 0;
    double sharpest = -1;
    for (size_t i = 0; i < n; ++i) {
        const Vec2 a = ring[i] - ring[(i + n - 1) % n], b = ring[(i + 1) % n] - ring[i];
        const double turn = angle_between(a.x, a.y, b.x, b.y);
        if (turn > sharpest) sharpest = turn, start = i;
    }
    Ring out(ring.begin() + static_cast<long>(start), ring.end());
    out.insert(out.end(), ring.begin(), ring.begin() + static_cast<long>(start));
    return out;
}

// ---- Boolean operations ----

using ExactPolygon = CGAL::Polygon_2<Exact>;
using ExactPolygonWithHoles = CGAL::Polygon_with_holes_2<Exact>;

ExactPolygon exact_polygon(const Ring& ring, bool counter_clockwise) {
    ExactPolygon polygon;
    for (Vec2 p : ring) polygon.push_back(Exact::Point_2(p.x, p.y));
    if (polygon.is_counterclockwise_oriented() != counter_clockwise) polygon.reverse_orientation();
    return polygon;
}

ExactPolygonWithHoles exact_polygon_with_holes(const Ring& outer, const std::vector<Ring>& holes) {
    std::vector<ExactPolygon> exact_holes;
    for (const Ring& h : holes) exact_holes.push_back(exact_polygon(h, false));
    return ExactPolygonWithHoles(exact_polygon(outer, true), exact_holes.begin(), exact_holes.end());
}

}  // namespace

int ring_orientation_exact(const Ring& ring) {
    if (ring.size() < 3) return 0;
    const auto points = points_of<Inexact>(ring);
    return static_cast<int>(CGAL::orientation_2(points.begin(), points.end(), Inexact()));
}

std::vector<Ring> split_at_crossings_exact(const Ring& ring) {
    const size_t n = ring.size();
    if (n < 3) return {};
    std::vector<CountedSegmentTraits::Curve_2> segments;
    segments.reserve(n);
    for (size_t i = 0; i < n; ++i) {
        const Vec2 a = ring[i], b = ring[(i + 1) % n];
        if (a == b) continue;
        segments.emplace_back(Exact::Segment_2(Exact::Point_2(a.x, a.y), Exact::Point_2(b.x, b.y)), 1u);
    }
    Arrangement arrangement;
    CGAL::insert(arrangement, segments.begin(), segments.end());  // one sweep for all

    // Even-odd: crossing an edge run along by an odd number of segments goes in or out.
    std::unordered_map<const void*, bool> inside{{&*arrangement.unbounded_face(), false}};
    std::vector<Arrangement::Face_const_handle> todo{arrangement.unbounded_face()};
    std::vector<Arrangement::Face_const_handle> inside_faces;  // in discovery order: deterministic
    auto visit = [&](Arrangement::Ccb_halfedge_const_circulator first, bool face_inside) {
        auto h = first;
        do {
            const auto neighbour = h->twin()->face();
            if (inside.count(&*neighbour)) continue;
            const bool neighbour_inside = face_inside != ((h->curve().data() & 1u) == 1u);
            inside[&*neighbour] = neighbour_inside;
            todo.push_back(neighbour);
            if (neighbour_inside) inside_faces.push_back(neighbour);
        } while (++h != first);
    };
    while (!todo.empty()) {
        const auto face = todo.back();
        todo.pop_back();
        const bool face_inside = inside[&*face];
        if (!face->is_unbounded()) visit(face->outer_ccb(), face_inside);
        for (auto ccb = face->inner_ccbs_begin(); ccb != face->inner_ccbs_end(); ++ccb) visit(*ccb, face_inside);
    }
    std::vector<Ring> loops;
    for (const auto& face : inside_faces) {
        add_loops(face->outer_ccb(), loops);
        for (auto ccb = face->inner_ccbs_begin(); ccb != face->inner_ccbs_end(); ++ccb) add_loops(*ccb, loops);
    }
    return loops;
}

std::vector<Ring> simplify_keeping_topology(const std::vector<Ring>& rings, double max_angle_deg) {
    SimplifyTriangulation triangulation;
    // Four points well outside the rings: Polyline_simplification_2's removability test walks
    // round a vertex's neighbours and refuses every vertex on the convex hull (it meets the
    // infinite vertex there), which would keep every convex corner of an outline.
    Box2 box;
    for (const Ring& ring : rings)
        for (Vec2 p : ring) box.extend(p);
    if (box.empty()) return rings;
    const double margin = 1 + std::max(box.max.x - box.min.x, box.max.y - box.min.y);
    for (Vec2 corner : {Vec2{box.min.x - margin, box.min.y - margin}, Vec2{box.max.x + margin, box.min.y - margin},
                        Vec2{box.max.x + margin, box.max.y + margin}, Vec2{box.min.x - margin, box.max.y + margin}})
        triangulation.insert(Inexact::Point_2(corner.x, corner.y));
    std::vector<SimplifyTriangulation::Constraint_id> ids;
    for (const Ring& ring : rings) {
        const auto points = points_of<Inexact>(starting_at_sharpest_corner(ring));
        ids.push_back(triangulation.insert_constraint(points.begin(), points.end(), true));
    }
    PS::simplify(triangulation, DirectionSpreadCost(), PS::Stop_above_cost_threshold(max_angle_deg * kPi / 180));
    std::vector<Ring> out;
    for (const auto& id : ids) {
        Ring ring;
        for (auto v = triangulation.vertices_in_constraint_begin(id); v != triangulation.vertices_in_constraint_end(id); ++v)
            ring.push_back({(*v)->point().x(), (*v)->point().y()});
        if (!ring.empty()) ring.pop_back();  // a closed constraint ends where it starts
        out.push_back(std::move(ring));
    }
    // Rings that cross (pieces rounded to float may, slightly) get their crossing points
    // inserted by the triangulation: then nothing is simplified, as no point may move or appear.
    for (size_t i = 0; i < rings.size(); ++i) {
        std::vector<std::pair<double, double>> given;
        for (Vec2 p : rings[i]) given.push_back({p.x, p.y});
        std::sort(given.begin(), given.end());
        for (Vec2 p : out[i])
            if (!std::binary_search(given.begin(), given.end(), std::make_pair(p.x, p.y))) return rings;
    }
    return out;
}

double overlap_area_exact(const Ring& piece, const Ring& outer, const std::vector<Ring>& holes) {
    std::list<ExactPolygonWithHoles> parts;
    CGAL::intersection(exact_polygon(piece, true), exact_polygon_with_holes(outer, holes), std::back_inserter(parts));
    Exact::FT area = 0;
    for (const ExactPolygonWithHoles& part : parts) {
        area += part.outer_boundary().area();
        for (auto h = part.holes_begin(); h != part.holes_end(); ++h) area += h->area();  // holes are clockwise
    }
    return CGAL::to_double(area);
}

bool polygon_is_valid_exact(const Ring& outer, const std::vector<Ring>& holes) {
    if (holes.empty()) {
        // The same check for the common case, on exact predicates without the exact-construction
        // kernel the general check needs (which cost many times the whole clean-up:
        // docs/bench/2026-11-buildings.md).
        if (outer.size() < 3) return false;
        const auto points = points_of<Inexact>(outer);
        return CGAL::is_simple_2(points.begin(), points.end(), Inexact()) &&
               CGAL::orientation_2(points.begin(), points.end(), Inexact()) == CGAL::COUNTERCLOCKWISE;
    }
    // As given: no reorienting, the check covers orientation too.
    auto as_is = [](const Ring& ring) {
        const auto points = points_of<Exact>(ring);
        return ExactPolygon(points.begin(), points.end());
    };
    std::vector<ExactPolygon> exact_holes;
    for (const Ring& h : holes) exact_holes.push_back(as_is(h));
    const ExactPolygonWithHoles polygon(as_is(outer), exact_holes.begin(), exact_holes.end());
    return CGAL::is_valid_polygon_with_holes(polygon, CGAL::Gps_segment_traits_2<Exact>());
}

}  // namespace citygen
