// The one translation unit of the renderer that includes CGAL (its headers compile slowly).
#include "render/geometry/triangulate_polygon.h"

#include <algorithm>
#include <list>

#include <CGAL/Constrained_Delaunay_triangulation_2.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Triangulation_face_base_with_info_2.h>
#include <CGAL/Triangulation_vertex_base_with_info_2.h>

namespace citygen {

namespace {

// Faces inside the polygon have an odd nesting level: the infinite face is 0, crossing one
// constrained edge (the outer ring) gives 1, crossing a hole's ring gives 2, and so on.
struct FaceNesting {
    int level = -1;
    bool inside() const { return level % 2 == 1; }
};

using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using VertexBase = CGAL::Triangulation_vertex_base_with_info_2<uint32_t, Kernel>;
using FaceBaseInfo = CGAL::Triangulation_face_base_with_info_2<FaceNesting, Kernel>;
using FaceBase = CGAL::Constrained_triangulation_face_base_2<Kernel, FaceBaseInfo>;
using Tds = CGAL::Triangulation_data_structure_2<VertexBase, FaceBase>;
// Exact_predicates_tag: crossing ring edges (dirty OSM data) are split instead of throwing.
using Cdt = CGAL::Constrained_Delaunay_triangulation_2<Kernel, Tds, CGAL::Exact_predicates_tag>;

void flood_nesting(Cdt& cdt, Cdt::Face_handle start, int level, std::list<Cdt::Edge>& border) {
    if (start->info().level != -1) return;
    std::list<Cdt::Face_handle> queue{start};
    while (!queue.empty()) {
        Cdt::Face_handle face = queue.front();
        queue.pop_front();
        if (face->info().level != -1) continue;
        face->info().level = level;
        for (int i = 0; i < 3; ++i) {
            Cdt::Face_handle next = face->neighbor(i);
            if (next->info().level != -1) continue;
            if (cdt.is_constrained(Cdt::Edge(face, i))) border.push_back(Cdt::Edge(face, i));
            else queue.push_back(next);
        }
    }
}

void mark_nesting(Cdt& cdt) {
    std::list<Cdt::Edge> border;
    flood_nesting(cdt, cdt.infinite_face(), 0, border);
    while (!border.empty()) {
        const Cdt::Edge e = border.front();
        border.pop_front();
        Cdt::Face_handle next = e.first->neighbor(e.second);
        if (next->info().level == -1) flood_nesting(cdt, next, e.first->info().level + 1, border);
    }
}

void insert_ring(Cdt& cdt, const Ring& ring) {
    std::vector<Cdt::Vertex_handle> handles;
    handles.reserve(ring.size());
    for (Vec2 p : ring) handles.push_back(cdt.insert(Cdt::Point(p.x, p.y)));
    for (size_t i = 0; i < handles.size(); ++i) {
        Cdt::Vertex_handle a = handles[i], b = handles[(i + 1) % handles.size()];
        if (a != b) cdt.insert_constraint(a, b);
    }
}

PolygonTriangulation fan_convex(const Ring& ring) {
    PolygonTriangulation out;
    out.points = ring;
    if (signed_area(ring) < 0) std::reverse(out.points.begin(), out.points.end());
    for (uint32_t i = 1; i + 1 < out.points.size(); ++i) {
        const Vec2 a = out.points[0], b = out.points[i], c = out.points[i + 1];
        if (cross(b - a, c - a) > 0) out.triangles.push_back({0, i, i + 1});
    }
    return out;
}

}  // namespace

PolygonTriangulation triangulate_polygon(const Ring& outer, const std::vector<Ring>& holes) {
    if (outer.size() < 3) return {};
    if (holes.empty() && ring_is_convex(outer)) return fan_convex(outer);

    Cdt cdt;
    insert_ring(cdt, outer);
    for (const Ring& hole : holes)
        if (hole.size() >= 3) insert_ring(cdt, hole);
    // Identical or collinear points give a 0- or 1-dimensional triangulation with no faces to
    // walk (its "faces" have no neighbours): nothing to cover.
    if (cdt.dimension() < 2) return {};
    mark_nesting(cdt);

    PolygonTriangulation out;
    uint32_t next_index = 0;
    for (Cdt::Vertex_handle v : cdt.finite_vertex_handles()) {
        v->info() = next_index++;
        out.points.emplace_back(v->point().x(), v->point().y());
    }
    for (Cdt::Face_handle f : cdt.finite_face_handles()) {
        if (!f->info().inside()) continue;
        out.triangles.push_back({f->vertex(0)->info(), f->vertex(1)->info(), f->vertex(2)->info()});
    }
    return out;
}

}  // namespace citygen
