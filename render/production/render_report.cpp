#include "render/production/render_report.h"

#include <cinttypes>
#include <fstream>
#include <string>
#include <vector>

#include "render/materials/materials.h"

namespace citygen {

uint64_t peak_rss_bytes() {
    std::ifstream status("/proc/self/status");
    for (std::string line; std::getline(status, line);)
        if (line.rfind("VmHWM:", 0) == 0) return std::stoull(line.substr(6)) * 1024;  // kB
    return 0;
}

void print_memory_info(const RenderScene& scene, FILE* out) {
    const int64_t embree = scene.embree_bytes();
    const size_t buffers = scene.buffer_bytes();
    std::fprintf(out, "memory: Embree holds %.1f MB (peak %.1f MB), our geometry buffers %.1f MB, peak RSS %.1f MB\n",
                 embree / 1e6, scene.embree_peak_bytes() / 1e6, buffers / 1e6, peak_rss_bytes() / 1e6);
    std::fprintf(out, "embree_bytes: %" PRId64 "\nembree_peak_bytes: %" PRId64 "\nbuffer_bytes: %zu\n", embree,
                 scene.embree_peak_bytes(), buffers);
    std::fprintf(out, "geometry_bytes: %" PRId64 "\npeak_rss_bytes: %" PRIu64 "\n",
                 embree + static_cast<int64_t>(buffers), peak_rss_bytes());
    // Our buffers per class (a class may have several geometries), e.g. terrain stored vs procedural.
    std::vector<size_t> per_kind;
    for (const auto& g : scene.geometries()) {
        const size_t k = static_cast<size_t>(g->kind());
        if (per_kind.size() <= k) per_kind.resize(k + 1, 0);
        per_kind[k] += g->buffer_bytes();
    }
    for (size_t k = 0; k < per_kind.size(); ++k)
        if (per_kind[k] > 0)
            std::fprintf(out, "buffer_bytes_%s: %zu\n", to_string(static_cast<ObjectKind>(k)), per_kind[k]);
}

void print_geometry_info(const RenderScene& scene, FILE* out) {
    uint64_t triangles = 0, primitives = 0;
    for (const auto& g : scene.geometries()) {
        std::fprintf(out, "%s: %s, %" PRIu64 " %s, %.1f MB of buffers\n", to_string(g->kind()), to_string(g->mode()),
                     g->primitive_count(), g->mode() == GeometryMode::Stored ? "triangles" : "primitives",
                     g->buffer_bytes() / 1e6);
        std::fprintf(out, "triangles_%s: %" PRIu64 "\nprimitives_%s: %" PRIu64 "\n", to_string(g->kind()),
                     g->triangle_count(), to_string(g->kind()), g->primitive_count());
        // Stored meshes: triangles per surface material too (e.g. how much of a facade is glass).
        if (const TriangleMesh* mesh = g->stored_mesh()) {
            static const MaterialTable materials = default_materials();
            std::vector<uint64_t> per_material(materials.size(), 0);
            for (uint16_t m : mesh->face_material)
                if (m < per_material.size()) ++per_material[m];
            for (size_t m = 0; m < per_material.size(); ++m)
                if (per_material[m] > 0)
                    std::fprintf(out, "triangles_%s_%s: %" PRIu64 "\n", to_string(g->kind()), materials[m].name.c_str(),
                                 per_material[m]);
        }
        triangles += g->triangle_count();
        primitives += g->primitive_count();
    }
    std::fprintf(out, "triangles: %" PRIu64 "\nprimitives: %" PRIu64 "\n", triangles, primitives);
}

}  // namespace citygen
