// CGAL's straight skeleton, in a translation unit of its own (its headers compile slowly; the
// footprint operations are in cgal_footprint.cpp).
#include "osmparse/roofs/roof_skeleton.h"

#include <algorithm>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_with_holes_2.h>
#include <CGAL/create_offset_polygons_2.h>
#include <CGAL/create_straight_skeleton_from_polygon_with_holes_2.h>

namespace citygen {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Polygon = CGAL::Polygon_2<Kernel>;
using PolygonWithHoles = CGAL::Polygon_with_holes_2<Kernel>;

// Relative to `origin`: small coordinates keep CGAL's filtered predicates certain more often, so
// it falls back to exact arithmetic less (several times faster on city coordinates).
Polygon to_cgal(const Ring& ring, Vec2 origin) {
    Polygon p;
    for (Vec2 v : ring) p.push_back(Kernel::Point_2(v.x - origin.x, v.y - origin.y));
    return p;
}
}  // namespace

bool straight_skeleton_faces(const Ring& outer, const std::vector<Ring>& holes, std::vector<SkeletonFace>* faces) {
    faces->clear();
    try {
        const Vec2 origin = outer.empty() ? Vec2{0, 0} : outer[0];
        PolygonWithHoles polygon(to_cgal(outer, origin));
        for (const Ring& hole : holes) polygon.add_hole(to_cgal(hole, origin));
        if (!polygon.outer_boundary().is_simple() || !polygon.outer_boundary().is_counterclockwise_oriented())
            return false;
        const auto skeleton = CGAL::create_interior_straight_skeleton_2(polygon, Kernel());
        if (!skeleton) return false;
        for (auto face = skeleton->faces_begin(); face != skeleton->faces_end(); ++face) {
            SkeletonFace out;
            auto h = face->halfedge();
            const auto first = h;
            do {
                const auto& p = h->vertex()->point();
                out.points.push_back({CGAL::to_double(p.x()) + origin.x, CGAL::to_double(p.y()) + origin.y});
                out.times.push_back(CGAL::to_double(h->vertex()->time()));
                h = h->next();
                if (out.points.size() > 100000) return false;  // a broken structure, not a face
            } while (h != first);
            faces->push_back(std::move(out));
        }
    } catch (const std::exception&) {
        faces->clear();
        return false;
    }
    return !faces->empty();
}

bool inset_polygon(const Ring& outer, double distance, std::vector<Ring>* out) {
    out->clear();
    try {
        const Vec2 origin = outer.empty() ? Vec2{0, 0} : outer[0];
        const Polygon polygon = to_cgal(outer, origin);
        if (!polygon.is_simple() || !polygon.is_counterclockwise_oriented()) return false;
        for (const auto& piece : CGAL::create_interior_skeleton_and_offset_polygons_2(distance, polygon)) {
            if (!piece) continue;
            Ring ring;
            for (auto v = piece->vertices_begin(); v != piece->vertices_end(); ++v)
                ring.push_back({CGAL::to_double(v->x()) + origin.x, CGAL::to_double(v->y()) + origin.y});
            if (signed_area(ring) < 0) std::reverse(ring.begin(), ring.end());
            out->push_back(std::move(ring));
        }
    } catch (const std::exception&) {
        out->clear();
        return false;
    }
    return true;
}

}  // namespace citygen
