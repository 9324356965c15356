#include "render/geometry/wall_geometry.h"

#include "common/retaining_wall.h"
#include "render/materials/materials.h"

namespace citygen {

uint16_t retaining_wall_material(WallMaterial material) {
    switch (material) {
        case WallMaterial::Stone: return kRetainingStone;
        case WallMaterial::Brick: return kRetainingBrick;
        case WallMaterial::Wood: return kRetainingWood;
        default: return kRetainingConcrete;
    }
}

std::vector<PlanarFace> retaining_wall_faces(const Scene& scene, const RetainingWall& wall) {
    std::vector<PlanarFace> faces;
    const std::vector<WallStation> stations = wall_stations(scene, wall);
    if (stations.size() < 2) return faces;
    const uint16_t m = retaining_wall_material(wall.material);
    const auto at = [](Vec2 p, double z) { return Vec3{p.x, p.y, z}; };
    for (size_t k = 0; k + 1 < stations.size(); ++k) {
        const WallStation &s = stations[k], &e = stations[k + 1];
        // The low side's face looks right, the high side's left (a counter-clockwise front).
        faces.push_back({{at(s.right, s.bottom), at(e.right, e.bottom), at(e.right, e.top), at(s.right, s.top)}, m});
        faces.push_back({{at(e.left, e.bottom), at(s.left, s.bottom), at(s.left, s.top), at(e.left, e.top)}, m});
        faces.push_back({{at(s.right, s.top), at(e.right, e.top), at(e.left, e.top)}, m});
        faces.push_back({{at(s.right, s.top), at(e.left, e.top), at(s.left, s.top)}, m});
    }
    const bool closed = wall.line.size() > 3 && wall.line.front() == wall.line.back();
    if (!closed) {
        const WallStation &s = stations.front(), &e = stations.back();
        faces.push_back({{at(s.left, s.bottom), at(s.right, s.bottom), at(s.right, s.top), at(s.left, s.top)}, m});
        faces.push_back({{at(e.right, e.bottom), at(e.left, e.bottom), at(e.left, e.top), at(e.right, e.top)}, m});
    }
    return faces;
}

TriangleMesh build_stored_retaining_walls(const Scene& scene) {
    TriangleMesh mesh;
    mesh.kind = ObjectKind::RetainingWall;
    for (uint32_t i = 0; i < scene.retaining_walls.size(); ++i)
        add_faces(retaining_wall_faces(scene, scene.retaining_walls[i]), i, mesh);
    return mesh;
}

std::unique_ptr<ProceduralGeometry> build_procedural_retaining_walls(const Scene& scene) {
    ProceduralGeometry::SurfaceMaterials unused;
    unused.fill(kRetainingConcrete);
    auto geometry = std::make_unique<ProceduralGeometry>(ObjectKind::RetainingWall, unused);
    for (uint32_t i = 0; i < scene.retaining_walls.size(); ++i)
        add_faces(retaining_wall_faces(scene, scene.retaining_walls[i]), i, *geometry);
    return geometry;
}

}  // namespace citygen
