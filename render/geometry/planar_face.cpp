#include "render/geometry/planar_face.h"

namespace citygen {

void add_faces(const std::vector<PlanarFace>& faces, uint32_t object, TriangleMesh& mesh) {
    for (const PlanarFace& f : faces) {
        const uint32_t first = mesh.add_vertex(f.points[0]);
        for (size_t k = 1; k < f.points.size(); ++k) mesh.add_vertex(f.points[k]);
        for (uint32_t k = 1; k + 1 < f.points.size(); ++k) mesh.add_triangle(first, first + k, first + k + 1, object, f.material);
    }
}

void add_faces(const std::vector<PlanarFace>& faces, uint32_t object, ProceduralGeometry& geometry) {
    for (const PlanarFace& f : faces) geometry.add_face(object, f.points, f.material);
}

}  // namespace citygen
