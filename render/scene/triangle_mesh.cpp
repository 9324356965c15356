#include "render/scene/triangle_mesh.h"

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace citygen {

void advise_huge_pages(const void* data, size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    constexpr uintptr_t kHugePage = uintptr_t{2} << 20;
    const auto start = reinterpret_cast<uintptr_t>(data);
    const uintptr_t first = (start + kHugePage - 1) & ~(kHugePage - 1), end = (start + bytes) & ~(kHugePage - 1);
    if (end > first) ::madvise(reinterpret_cast<void*>(first), end - first, MADV_HUGEPAGE);
#else
    (void)data;
    (void)bytes;
#endif
}

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
