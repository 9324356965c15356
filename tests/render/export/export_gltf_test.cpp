// --export-gltf read back with tinygltf: a node per building carrying its OSM id, a node per
// other class, every triangle once, the materials used, y-up; bad requests write nothing.
#include <algorithm>
#include <filesystem>
#include <set>

#include <gtest/gtest.h>
#include <tiny_gltf.h>

#include "common/scene_io.h"
#include "tests/test_support.h"

using namespace citygen;
using namespace citygen::test;

namespace {


long info_value(const std::string& text, const std::string& key) {
    const size_t at = ("\n" + text).find("\n" + key + ": ");
    return at == std::string::npos ? -1 : std::stol(text.substr(at + key.size() + 2));
}

}  // namespace

TEST(ExportGltf, RoundTripKeepsNodesMaterialsTrianglesAndOsmIds) {
    TempDir dir;
    const std::string scene_path = dir.file("tiny.scene"), glb = dir.file("tiny.glb");
    ASSERT_EQ(run_command(quoted(osmparse_binary()) + " " + quoted(source_path("tests/data/tiny_roundabout.osm")) +
                          " -q -o " + quoted(scene_path))
                  .exit_code,
              0);
    const CommandResult r = run_command(quoted(render_binary()) + " " + quoted(scene_path) + " --export-gltf " +
                                        quoted(glb) + " --print-scene-geometry-info -q");
    ASSERT_EQ(r.exit_code, 0) << r.err;

    tinygltf::Model model;
    tinygltf::TinyGLTF loader;
    std::string err, warn;
    ASSERT_TRUE(loader.LoadBinaryFromFile(&model, &err, &warn, glb)) << err;

    // What the renderer built: classes and materials with triangles (from the info lines).
    const Scene scene = load_scene(scene_path);
    std::set<std::string> classes, material_names;
    std::stringstream lines(r.out);
    for (std::string line; std::getline(lines, line);) {
        if (line.rfind("triangles_", 0) != 0) continue;
        const std::string key = line.substr(10, line.find(':') - 10);
        const size_t underscore = key.find('_');
        if (underscore == std::string::npos) classes.insert(key);
        else material_names.insert(key.substr(underscore + 1));
    }
    ASSERT_TRUE(classes.count("building"));
    EXPECT_EQ(model.nodes.size(), scene.buildings.size() + classes.size() - 1);
    EXPECT_EQ(model.scenes.at(0).nodes.size(), model.nodes.size());
    EXPECT_EQ(model.materials.size(), material_names.size());
    for (const tinygltf::Material& m : model.materials) EXPECT_TRUE(material_names.count(m.name)) << m.name;

    // Every building once, by its OSM reference; every triangle once.
    std::multiset<std::string> osm_ids, expected_ids;
    for (const Building& b : scene.buildings) expected_ids.insert(to_string(b.osm));
    long triangles = 0;
    double lowest_y = 1e30, highest_y = -1e30;
    for (const tinygltf::Node& node : model.nodes) {
        ASSERT_GE(node.mesh, 0);
        if (node.extras.Has("osm_id")) {
            osm_ids.insert(node.extras.Get("osm_id").Get<std::string>());
            EXPECT_EQ(node.name, "building " + node.extras.Get("osm_id").Get<std::string>());
            EXPECT_GT(node.extras.Get("height_m").GetNumberAsDouble(), 0);
        } else {
            EXPECT_TRUE(classes.count(node.extras.Get("class").Get<std::string>())) << node.name;
        }
        for (const tinygltf::Primitive& p : model.meshes.at(node.mesh).primitives) {
            EXPECT_EQ(p.mode, TINYGLTF_MODE_TRIANGLES);
            triangles += static_cast<long>(model.accessors.at(p.indices).count / 3);
            const tinygltf::Accessor& position = model.accessors.at(p.attributes.at("POSITION"));
            lowest_y = std::min(lowest_y, position.minValues.at(1));
            highest_y = std::max(highest_y, position.maxValues.at(1));
        }
    }
    EXPECT_EQ(osm_ids, expected_ids);
    EXPECT_EQ(triangles, info_value(r.out, "triangles"));
    // y is up: from the ground (z = 0 in the scene) to the tallest roof.
    double tallest = 0;
    for (const Building& b : scene.buildings) tallest = std::max(tallest, b.height);
    EXPECT_NEAR(lowest_y, scene.ground.z, 0.5);
    EXPECT_NEAR(highest_y, scene.ground.z + tallest, 0.5);
}

TEST(ExportGltf, BadRequestsGiveOneLineAndNoFile) {
    TempDir dir;
    const std::string scene_path = dir.file("tiny.scene");
    ASSERT_EQ(run_command(quoted(osmparse_binary()) + " " + quoted(source_path("tests/data/tiny_roundabout.osm")) +
                          " -q -o " + quoted(scene_path))
                  .exit_code,
              0);
    for (const std::string& args : {" --procedural --export-gltf " + quoted(dir.file("a.glb")),
                                    " --export-gltf " + quoted(dir.file("a.gltf")),
                                    std::string(" --export-gltf /nonexistent-dir/a.glb")}) {
        const CommandResult r = run_command(quoted(render_binary()) + " " + quoted(scene_path) + args + " -q");
        EXPECT_NE(r.exit_code, 0) << args;
        EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
        EXPECT_EQ(r.err.rfind("render: ", 0), 0u) << r.err;
    }
    for (const auto& entry : std::filesystem::directory_iterator(dir.path()))
        EXPECT_EQ(entry.path().filename().string(), "tiny.scene");
}
