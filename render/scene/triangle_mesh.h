// A stored triangle mesh for one object class: what stored builders produce, what Embree
// traces (its buffers are shared with Embree, not copied) and what --export-ply writes.
#pragma once

#include <cstdint>
#include <vector>

#include "common/geometry.h"
#include "render/scene/geometry_mode.h"

namespace citygen {

struct TriangleMesh {
    ObjectKind kind = ObjectKind::None;
    std::vector<float> vertices;           // x, y, z per vertex (+ padding Embree reads past the end)
    std::vector<uint32_t> indices;         // 3 per triangle; counter-clockwise seen from the front
    std::vector<uint32_t> face_object;     // per triangle: index of the scene object it belongs to
    std::vector<uint16_t> face_material;   // per triangle: MaterialId
    // Facade panes only (hit.h's wall and cell), ascending by first triangle; each pane is the
    // two triangles from first_triangle on. Kept sparse: a few percent of a facade's triangles.
    struct PaneCell {
        uint32_t first_triangle, wall, cell;
    };
    std::vector<PaneCell> pane_cells;

    // Room for this many vertices (+ Embree's padding) and triangles, allocated once and marked
    // for huge pages before their first write (common/huge_page_advice.h): a stored city's
    // buffers are hundreds of megabytes, which tracing reads through Embree's compact BVH.
    void reserve(size_t vertex_count, size_t triangle_count);
    size_t vertex_count() const { return vertices.size() / 3; }
    size_t triangle_count() const { return face_object.size(); }

    uint32_t add_vertex(Vec3 p) {
        vertices.push_back(static_cast<float>(p.x));
        vertices.push_back(static_cast<float>(p.y));
        vertices.push_back(static_cast<float>(p.z));
        return static_cast<uint32_t>(vertex_count() - 1);
    }
    void add_triangle(uint32_t a, uint32_t b, uint32_t c, uint32_t object, uint16_t material) {
        indices.insert(indices.end(), {a, b, c});
        face_object.push_back(object);
        face_material.push_back(material);
    }
    // Two triangles a-b-c, a-c-d.
    void add_quad(Vec3 a, Vec3 b, Vec3 c, Vec3 d, uint32_t object, uint16_t material) {
        const uint32_t ia = add_vertex(a), ib = add_vertex(b), ic = add_vertex(c), id = add_vertex(d);
        add_triangle(ia, ib, ic, object, material);
        add_triangle(ia, ic, id, object, material);
    }
    Vec3 vertex(uint32_t i) const { return {vertices[3 * i], vertices[3 * i + 1], vertices[3 * i + 2]}; }
    size_t bytes() const {
        return vertices.capacity() * sizeof(float) + indices.capacity() * sizeof(uint32_t) +
               face_object.capacity() * sizeof(uint32_t) + face_material.capacity() * sizeof(uint16_t) +
               pane_cells.capacity() * sizeof(PaneCell);
    }
};

}  // namespace citygen
