#include "render/export/export_ply.h"

#include <cstdio>
#include <cstring>

#include "common/error.h"
#include "common/scene_io.h"

namespace citygen {

namespace {

template <typename T>
void append(std::vector<uint8_t>& out, T value) {
    const size_t at = out.size();
    out.resize(at + sizeof(T));
    std::memcpy(&out[at], &value, sizeof(T));  // the hosts we build on are little-endian
}

}  // namespace

void export_ply(const RenderScene& scene, const MaterialTable& materials, const std::string& path) {
    size_t vertices = 0, faces = 0;
    for (const auto& g : scene.geometries()) {
        const TriangleMesh* mesh = g->stored_mesh();
        if (!mesh) throw Error(std::string("--export-ply: the ") + to_string(g->kind()) +
                               " geometry is procedural; export needs stored geometry");
        vertices += mesh->vertex_count();
        faces += mesh->triangle_count();
    }
    static const char* const kTypeNames[] = {"diffuse", "glossy", "mirror", "glass", "water"};
    static_assert(sizeof kTypeNames / sizeof *kTypeNames == static_cast<int>(MaterialType::Water) + 1,
                  "a name for every MaterialType");
    std::string material_comments;
    for (size_t id = 0; id < materials.size(); ++id) {
        const Material& m = materials[id];
        char line[256];
        std::snprintf(line, sizeof line, "comment material %zu %s %s %g %g %g %g %g %g %g %g\n", id, m.name.c_str(),
                      kTypeNames[static_cast<int>(m.type)], m.albedo.x, m.albedo.y, m.albedo.z, m.specular.x,
                      m.specular.y, m.specular.z, m.exponent, m.ior);
        material_comments += line;
    }
    const std::string header = "ply\nformat binary_little_endian 1.0\ncomment citygen render --export-ply\n" +
                               material_comments + "element vertex " + std::to_string(vertices) +
                               "\nproperty float x\nproperty float y\nproperty float z\n"
                               "element face " + std::to_string(faces) +
                               "\nproperty list uchar int vertex_indices\nproperty ushort material_index\n"
                               "end_header\n";
    std::vector<uint8_t> out(header.begin(), header.end());
    out.reserve(out.size() + vertices * 12 + faces * 15);
    for (const auto& g : scene.geometries())
        for (size_t i = 0; i < 3 * g->stored_mesh()->vertex_count(); ++i) append(out, g->stored_mesh()->vertices[i]);
    uint32_t first = 0;
    for (const auto& g : scene.geometries()) {
        const TriangleMesh& mesh = *g->stored_mesh();
        for (size_t t = 0; t < mesh.triangle_count(); ++t) {
            append<uint8_t>(out, 3);
            for (int k = 0; k < 3; ++k) append<int32_t>(out, static_cast<int32_t>(first + mesh.indices[3 * t + k]));
            append<uint16_t>(out, mesh.face_material[t]);
        }
        first += static_cast<uint32_t>(mesh.vertex_count());
    }
    write_file_atomically(path, out.data(), out.size());
}

}  // namespace citygen
