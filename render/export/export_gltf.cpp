#include "render/export/export_gltf.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <sstream>

#include <tiny_gltf.h>

#include "common/error.h"
#include "common/scene_io.h"

namespace citygen {

namespace {

// Roughness of a glossy lobe with this Phong exponent (the usual 2 / (n + 2) = alpha^2 match).
double roughness_of(const Material& m) {
    switch (m.type) {
        case MaterialType::Diffuse: return 1.0;
        case MaterialType::Glossy: return std::sqrt(2.0 / (m.exponent + 2));
        default: return 0.0;  // mirror, glass
    }
}

tinygltf::Material gltf_material(const Material& m) {
    tinygltf::Material out;
    out.name = m.name;
    const Color base = m.type == MaterialType::Diffuse || m.type == MaterialType::Glossy ? m.albedo : m.specular;
    out.pbrMetallicRoughness.baseColorFactor = {base.x, base.y, base.z, 1.0};
    out.pbrMetallicRoughness.metallicFactor = m.type == MaterialType::Mirror ? 1.0 : 0.0;
    out.pbrMetallicRoughness.roughnessFactor = roughness_of(m);
    const double peak = std::max({m.emission.x, m.emission.y, m.emission.z});
    if (peak > 0) {
        // glTF keeps emissive colour in [0, 1]; the rest goes to the strength extension.
        const double scale = std::max(1.0, peak);
        out.emissiveFactor = {m.emission.x / scale, m.emission.y / scale, m.emission.z / scale};
        if (scale > 1) {
            tinygltf::Value::Object strength{{"emissiveStrength", tinygltf::Value(scale)}};
            out.extensions["KHR_materials_emissive_strength"] = tinygltf::Value(strength);
        }
    }
    if (m.type == MaterialType::Glass) {
        tinygltf::Value::Object transmission{{"transmissionFactor", tinygltf::Value(1.0)}};
        out.extensions["KHR_materials_transmission"] = tinygltf::Value(transmission);
        tinygltf::Value::Object ior{{"ior", tinygltf::Value(m.ior)}};
        out.extensions["KHR_materials_ior"] = tinygltf::Value(ior);
    }
    return out;
}

// Appends raw bytes to the one buffer, 4-byte aligned (accessors need their component alignment).
size_t append_bytes(std::vector<unsigned char>& buffer, const void* data, size_t size) {
    buffer.resize((buffer.size() + 3) & ~size_t{3});
    const size_t offset = buffer.size();
    buffer.resize(offset + size);
    std::memcpy(buffer.data() + offset, data, size);
    return offset;
}

class GltfBuilder {
public:
    explicit GltfBuilder(const MaterialTable& materials) : materials_(materials) {
        model_.asset.version = "2.0";
        model_.asset.generator = "citygen render --export-gltf";
        model_.scenes.emplace_back();
        model_.defaultScene = 0;
    }

    // A node with one mesh made of the given triangles of `mesh`; returns the node index.
    int add_node(const std::string& name, const TriangleMesh& mesh, const std::vector<uint32_t>& triangles,
                 tinygltf::Value extras) {
        // The triangles' vertices, compacted and turned y-up.
        std::map<uint32_t, uint32_t> remap;
        std::vector<float> positions;
        float lo[3] = {1e30f, 1e30f, 1e30f}, hi[3] = {-1e30f, -1e30f, -1e30f};
        auto vertex = [&](uint32_t v) {
            auto [it, inserted] = remap.emplace(v, static_cast<uint32_t>(remap.size()));
            if (inserted) {
                const float p[3] = {mesh.vertices[3 * v], mesh.vertices[3 * v + 2], -mesh.vertices[3 * v + 1]};
                for (int c = 0; c < 3; ++c) {
                    positions.push_back(p[c]);
                    lo[c] = std::min(lo[c], p[c]);
                    hi[c] = std::max(hi[c], p[c]);
                }
            }
            return it->second;
        };
        // A primitive per material, in material order.
        std::map<uint16_t, std::vector<uint32_t>> indices_by_material;
        for (uint32_t t : triangles) {
            std::vector<uint32_t>& indices = indices_by_material[mesh.face_material[t]];
            for (int k = 0; k < 3; ++k) indices.push_back(vertex(mesh.indices[3 * t + k]));
        }
        tinygltf::Mesh gltf_mesh;
        gltf_mesh.name = name;
        const int position_accessor =
            add_accessor(positions.data(), positions.size() * sizeof(float), positions.size() / 3,
                         TINYGLTF_COMPONENT_TYPE_FLOAT, TINYGLTF_TYPE_VEC3, TINYGLTF_TARGET_ARRAY_BUFFER);
        model_.accessors[position_accessor].minValues = {lo[0], lo[1], lo[2]};
        model_.accessors[position_accessor].maxValues = {hi[0], hi[1], hi[2]};
        for (const auto& [material, indices] : indices_by_material) {
            tinygltf::Primitive primitive;
            primitive.mode = TINYGLTF_MODE_TRIANGLES;
            primitive.attributes["POSITION"] = position_accessor;
            primitive.indices = add_accessor(indices.data(), indices.size() * sizeof(uint32_t), indices.size(),
                                             TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, TINYGLTF_TYPE_SCALAR,
                                             TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER);
            primitive.material = material_index(material);
            gltf_mesh.primitives.push_back(primitive);
        }
        model_.meshes.push_back(gltf_mesh);
        tinygltf::Node node;
        node.name = name;
        node.mesh = static_cast<int>(model_.meshes.size() - 1);
        node.extras = std::move(extras);
        model_.nodes.push_back(node);
        const int index = static_cast<int>(model_.nodes.size() - 1);
        model_.scenes[0].nodes.push_back(index);
        return index;
    }

    std::string write_glb() {
        tinygltf::Buffer buffer;
        buffer.data = std::move(buffer_);
        model_.buffers.push_back(std::move(buffer));
        for (const char* extension : {"KHR_materials_emissive_strength", "KHR_materials_transmission",
                                      "KHR_materials_ior"})
            for (const tinygltf::Material& m : model_.materials)
                if (m.extensions.count(extension)) {
                    model_.extensionsUsed.push_back(extension);
                    break;
                }
        std::ostringstream out;
        tinygltf::TinyGLTF writer;
        if (!writer.WriteGltfSceneToStream(&model_, out, false, true)) throw Error("--export-gltf: tinygltf failed");
        return out.str();
    }

private:
    int add_accessor(const void* data, size_t bytes, size_t count, int component, int type, int target) {
        tinygltf::BufferView view;
        view.buffer = 0;
        view.byteOffset = append_bytes(buffer_, data, bytes);
        view.byteLength = bytes;
        view.target = target;
        model_.bufferViews.push_back(view);
        tinygltf::Accessor accessor;
        accessor.bufferView = static_cast<int>(model_.bufferViews.size() - 1);
        accessor.componentType = component;
        accessor.count = count;
        accessor.type = type;
        model_.accessors.push_back(accessor);
        return static_cast<int>(model_.accessors.size() - 1);
    }

    // Materials are written as first used, so the file holds only those it needs.
    int material_index(uint16_t id) {
        auto [it, inserted] = material_of_id_.emplace(id, static_cast<int>(model_.materials.size()));
        if (inserted) model_.materials.push_back(gltf_material(materials_.at(id)));
        return it->second;
    }

    const MaterialTable& materials_;
    tinygltf::Model model_;
    std::vector<unsigned char> buffer_;
    std::map<uint16_t, int> material_of_id_;
};

}  // namespace

void export_gltf(const Scene& scene, const RenderScene& render_scene, const MaterialTable& materials,
                 const std::string& path) {
    GltfBuilder builder(materials);
    for (const auto& g : render_scene.geometries()) {
        const TriangleMesh* mesh = g->stored_mesh();
        if (!mesh)
            throw Error(std::string("--export-gltf: the ") + to_string(g->kind()) +
                        " geometry is procedural; export needs stored geometry");
        if (mesh->triangle_count() == 0) continue;
        if (g->kind() == ObjectKind::Building) {
            // One node per building, its triangles in the order the mesh has them.
            std::map<uint32_t, std::vector<uint32_t>> triangles_of_building;
            for (uint32_t t = 0; t < mesh->triangle_count(); ++t) triangles_of_building[mesh->face_object[t]].push_back(t);
            for (const auto& [building, triangles] : triangles_of_building) {
                const Building& b = scene.buildings.at(building);
                tinygltf::Value::Object extras{{"osm_id", tinygltf::Value(to_string(b.osm))},
                                               {"height_m", tinygltf::Value(b.height)}};
                builder.add_node("building " + to_string(b.osm), *mesh, triangles, tinygltf::Value(extras));
            }
        } else {
            std::vector<uint32_t> all(mesh->triangle_count());
            for (uint32_t t = 0; t < all.size(); ++t) all[t] = t;
            tinygltf::Value::Object extras{{"class", tinygltf::Value(std::string(to_string(g->kind())))}};
            builder.add_node(to_string(g->kind()), *mesh, all, tinygltf::Value(extras));
        }
    }
    const std::string bytes = builder.write_glb();
    write_file_atomically(path, bytes.data(), bytes.size());
}

}  // namespace citygen
