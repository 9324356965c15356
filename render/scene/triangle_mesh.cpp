#include "render/scene/triangle_mesh.h"

#include "common/huge_page_advice.h"

namespace citygen {

void TriangleMesh::reserve(size_t vertex_count, size_t triangle_count) {
    vertices.reserve(3 * vertex_count + 4);
    indices.reserve(3 * triangle_count);
    face_object.reserve(triangle_count);
    face_material.reserve(triangle_count);
    advise_huge_pages(vertices.data(), vertices.capacity() * sizeof(float));
    advise_huge_pages(indices.data(), indices.capacity() * sizeof(uint32_t));
    advise_huge_pages(face_object.data(), face_object.capacity() * sizeof(uint32_t));
    advise_huge_pages(face_material.data(), face_material.capacity() * sizeof(uint16_t));
}

}  // namespace citygen
