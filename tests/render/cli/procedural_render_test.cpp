// Same picture in both geometry modes: a real extract parsed by osmparse and rendered by the
// render binary, stored vs procedural, compared through the EXR AOVs (id, depth) and beauty.
#include <gtest/gtest.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "common/scene_io.h"
#include "render/camera/camera.h"
#include "render/film/image_output.h"
#include "render/scene/geometry_mode.h"
#include "tests/render/test_exr.h"
#include "tests/test_support.h"

using namespace citygen::test;

namespace {


// Renders `scene` with the given geometry mode flags to an EXR with AOVs.
Exr render(const TempDir& dir, const std::string& scene, const std::string& name, const std::string& mode_flags,
           int threads = 2, const std::string& view = "--camera=-60,-80,8 --look-at=0,0,3 --fov 45", int spp = 4) {
    const std::string out = dir.file(name + ".exr");
    CommandResult r = run_command(render_binary() + " " + quoted(scene) + " -o " + quoted(out) +
                                  " --width 160 --height 90 --spp " + std::to_string(spp) + " --seed 3 --threads " +
                                  std::to_string(threads) + " --quiet " + view + " --aovs depth,id,albedo " + mode_flags);
    EXPECT_EQ(r.exit_code, 0) << r.err;
    return read_exr(out);
}

// The real extract both tests render: small, with facades filling most of the default view.
std::string tiny_roundabout_osm() {
    return std::string(CITYGEN_SHARED_DATA_DIR) + "/osm2streets/tiny_roundabout/input.osm";
}

std::string parse_to_scene(TempDir& dir, const std::string& osm) {
    const std::string scene = dir.file("tiny.scene");
    const CommandResult parsed = run_command(osmparse_binary() + " --quiet " + quoted(osm) + " -o " + quoted(scene));
    EXPECT_EQ(parsed.exit_code, 0) << parsed.err;
    return scene;
}

// How far two renders of one view (stored vs procedural) agree.
struct Comparison {
    int pixels = 0, same_id = 0, same_id_and_depth = 0, building_pixels = 0, lamp_pixels = 0;
    double psnr = 0;
};

// Same depth: within 1 mm, or 1e-5 of the distance far away (float depth); lamps within 1 cm
// (their stored facets stay within 2 mm of the analytic surfaces, stored_lamps.cpp), as trees.
constexpr float kLampDepthTolerance = 0.01f;

Comparison compare(const Exr& stored, const Exr& procedural) {
    Comparison r;
    EXPECT_GT(stored.width, 0);
    EXPECT_EQ(stored.width, procedural.width);
    EXPECT_EQ(stored.height, procedural.height);
    EXPECT_EQ(stored.names, procedural.names);
    const int kind = stored.channel("id.kind"), index = stored.channel("id.index"), depth = stored.channel("Z");
    EXPECT_GE(kind, 0);
    EXPECT_GE(index, 0);
    EXPECT_GE(depth, 0);
    if (stored.width == 0 || stored.pixels.size() != procedural.pixels.size() || kind < 0 || index < 0 || depth < 0)
        return r;
    const int pixels = r.pixels = stored.width * stored.height;
    for (int p = 0; p < pixels; ++p) {
        r.building_pixels += stored.at(p, kind) == 1.0f;  // ObjectKind::Building
        r.lamp_pixels += stored.at(p, kind) == 6.0f;      // ObjectKind::Lamp
        if (stored.at(p, kind) != procedural.at(p, kind) || stored.at(p, index) != procedural.at(p, index)) continue;
        ++r.same_id;
        const float tolerance =
            stored.at(p, kind) == 6.0f ? kLampDepthTolerance : std::max(1e-3f, 1e-5f * stored.at(p, depth));
        r.same_id_and_depth += std::abs(stored.at(p, depth) - procedural.at(p, depth)) <= tolerance;
    }
    // Beauty: PSNR over RGB of the displayed image (tone-mapped sRGB as in the PNG output, peak 1).
    // Not against the linear peak: that is often a sun glint thousands of times brighter than
    // the rest, which hides real differences. Both modes trace the same paths (same hits, and a
    // sampling frame that is continuous in the normal), so this is typically far above 40 dB;
    // the rare path that grazes an edge differently costs at most ~42 dB per pixel.
    double squared = 0;
    for (int p = 0; p < pixels; ++p) {
        for (int c = 0; c < 3; ++c) {
            const double a = citygen::tone_map(stored.at(p, c), 1), b = citygen::tone_map(procedural.at(p, c), 1);
            squared += (a - b) * (a - b);
        }
    }
    const double mse = squared / (3.0 * pixels);
    r.psnr = mse == 0 ? 1e9 : 10 * std::log10(1 / mse);
    return r;
}

void expect_same_picture(const Comparison& c) {
    EXPECT_GE(c.same_id, std::ceil(0.999 * c.pixels)) << c.pixels - c.same_id << " pixels differ in id";
    EXPECT_GE(c.same_id_and_depth, std::ceil(0.999 * c.pixels))
        << c.same_id - c.same_id_and_depth << " pixels with the same id differ in depth by more than 1 mm (lamps 1 cm)";
    EXPECT_GE(c.psnr, 40.0);
}

// A street-level view of the scene's first lamp from a few metres away, its globe in the frame.
std::string view_of_first_lamp(const std::string& scene_path) {
    const citygen::Scene scene = citygen::load_scene(scene_path);
    if (scene.lamps.empty()) return "";
    const citygen::Vec3 p = scene.lamps[0].position;
    const double z = scene.ground.z + p.z;
    char view[256];
    std::snprintf(view, sizeof view, "--camera=%.3f,%.3f,%.3f --look-at=%.3f,%.3f,%.3f --fov 40", p.x - 6, p.y - 5,
                  z + 1.7, p.x, p.y, z + p.z + scene.lamps[0].height * 0.6);
    return view;
}

}  // namespace

TEST(ProceduralRender, SamePictureAsStoredOnARealExtract) {
    const std::string osm = tiny_roundabout_osm();
    if (!std::filesystem::exists(osm)) GTEST_SKIP() << osm << " not available";
    TempDir dir;
    const std::string scene = parse_to_scene(dir, osm);

    const Exr stored = render(dir, scene, "stored", "");
    const Exr procedural = render(dir, scene, "procedural", "--procedural");
    const Comparison c = compare(stored, procedural);
    EXPECT_GT(c.building_pixels, c.pixels / 5) << "the view should be mostly facades";
    expect_same_picture(c);
}

TEST(ProceduralRender, SameImageWithOneOrTwoThreads) {
    // The callbacks keep no state between rays, so the thread count cannot change a pixel.
    const std::string osm = tiny_roundabout_osm();
    if (!std::filesystem::exists(osm)) GTEST_SKIP() << osm << " not available";
    TempDir dir;
    const std::string scene = parse_to_scene(dir, osm);
    const Exr one = render(dir, scene, "one", "--procedural", 1);
    const Exr two = render(dir, scene, "two", "--procedural", 2);
    ASSERT_GT(one.width, 0);
    ASSERT_EQ(one.pixels.size(), two.pixels.size());
    EXPECT_TRUE(one.pixels == two.pixels);
}

TEST(ProceduralRender, SameRoofsAndColoursOnTheBundledExample) {
    // Neukolln has tagged and default pitched roofs, tagged and default colours and materials.
    // Trees are left out: they have their own comparison (SameTreesAsStored).
    TempDir dir;
    const std::string scene = dir.file("neukolln.scene");
    const CommandResult parsed = run_command(osmparse_binary() + " --quiet --trees none " +
                                             quoted(source_path("examples/neukolln.osm.bz2")) + " -o " + quoted(scene));
    ASSERT_EQ(parsed.exit_code, 0) << parsed.err;
    const std::string view = "--camera=-40,-150,60 --look-at=0,-60,0 --fov 45";
    // Lamps, too, have their own comparison (SameLampsAsStored): procedural in both renders here.
    const Exr stored = render(dir, scene, "stored", "--geometry-lamps procedural", 2, view);
    const Exr procedural = render(dir, scene, "procedural", "--procedural", 2, view);
    ASSERT_GT(stored.width, 0);
    ASSERT_EQ(stored.names, procedural.names);
    const int kind = stored.channel("id.kind"), index = stored.channel("id.index"), depth = stored.channel("Z");
    const int albedo = stored.channel("albedo.R");
    ASSERT_GE(albedo, 0);
    const int pixels = stored.width * stored.height;
    int same = 0, buildings = 0;
    std::vector<float> building_albedos;
    for (int p = 0; p < pixels; ++p) {
        if (stored.at(p, kind) == 1.0f) {
            ++buildings;
            building_albedos.push_back(stored.at(p, albedo));
        }
        // Overlapping land cover polygons of one class lie at one height: which of them a ray
        // meets first is a tie that Embree's triangle and our own intersector may break apart
        // (it differs with the CPU's vector width), with the same picture either way.
        const bool tie = stored.at(p, kind) == static_cast<float>(citygen::ObjectKind::LandCover);
        same += stored.at(p, kind) == procedural.at(p, kind) &&
                (stored.at(p, index) == procedural.at(p, index) || tie) &&
                std::abs(stored.at(p, depth) - procedural.at(p, depth)) <= 1e-3f &&
                std::abs(stored.at(p, albedo) - procedural.at(p, albedo)) <= 1e-3f;
    }
    EXPECT_GT(buildings, pixels / 5);
    EXPECT_GE(same, std::ceil(0.995 * pixels)) << pixels - same << " pixels differ";
    double squared = 0;  // beauty, as displayed (see SamePictureAsStoredOnARealExtract)
    for (int p = 0; p < pixels; ++p)
        for (int c = 0; c < 3; ++c) {
            const double a = citygen::tone_map(stored.at(p, c), 1), b = citygen::tone_map(procedural.at(p, c), 1);
            squared += (a - b) * (a - b);
        }
    const double mse = squared / (3.0 * pixels);
    EXPECT_GE(mse == 0 ? 1e9 : 10 * std::log10(1 / mse), 40.0) << "PSNR in dB";
    // Colours vary: the albedo AOV on buildings is not one value.
    std::sort(building_albedos.begin(), building_albedos.end());
    ASSERT_FALSE(building_albedos.empty());
    EXPECT_GT(building_albedos[building_albedos.size() * 9 / 10] - building_albedos[building_albedos.size() / 10],
              0.05f);
}

TEST(ProceduralRender, UserTexturesReplacePatternsInBothModes) {
    TempDir dir;
    // A 64x64 checker as every wall material's texture: the albedo on walls takes two values.
    OIIO::ImageBuf checker(OIIO::ImageSpec(64, 64, 3, OIIO::TypeDesc::UINT8));
    const float dark[3] = {0.2f, 0.2f, 0.2f}, light[3] = {0.9f, 0.9f, 0.9f};
    OIIO::ImageBufAlgo::checker(checker, 8, 8, 1, dark, light);
    const std::string textures = dir.file("textures");
    std::filesystem::create_directory(textures);
    for (const char* name : {"plaster", "brick", "concrete", "stone", "wood", "metal"})
        ASSERT_TRUE(checker.write(textures + "/" + name + ".png"));
    const std::string scene = dir.file("roofs.scene");
    ASSERT_EQ(run_command(osmparse_binary() + " --quiet " + quoted(source_path("tests/data/roofs.osm")) + " -o " +
                          quoted(scene))
                  .exit_code,
              0);
    const std::string view = "--camera=-1,-70,7 --look-at=-4,-60,8 --fov 45";
    const Exr plain = render(dir, scene, "plain", "", 2, view);
    const Exr stored = render(dir, scene, "stored", "--texture-dir " + quoted(textures), 2, view);
    const Exr procedural = render(dir, scene, "procedural", "--procedural --texture-dir " + quoted(textures), 2, view);
    ASSERT_GT(stored.width, 0);
    const int albedo = stored.channel("albedo.G"), kind = stored.channel("id.kind");
    int walls = 0, differs_from_plain = 0, same_modes = 0;
    for (int p = 0; p < stored.width * stored.height; ++p) {
        if (stored.at(p, kind) != 1.0f) continue;
        ++walls;
        differs_from_plain += std::abs(stored.at(p, albedo) - plain.at(p, albedo)) > 0.05f;
        same_modes += std::abs(stored.at(p, albedo) - procedural.at(p, albedo)) <= 1e-3f;
    }
    EXPECT_GT(walls, 1000);
    EXPECT_GT(differs_from_plain, walls / 4) << "the checker shows";
    EXPECT_GE(same_modes, walls * 99 / 100);

    const CommandResult bad = run_command(render_binary() + " " + quoted(scene) + " -o " + quoted(dir.file("x.png")) +
                                          " --quiet --texture-dir " + quoted(dir.file("missing")));
    EXPECT_NE(bad.exit_code, 0);
    EXPECT_EQ(std::count(bad.err.begin(), bad.err.end(), '\n'), 1) << bad.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("x.png")));
}

TEST(ProceduralRender, SameLampsAsStored) {
    // Lamps are triangles in stored mode and analytic cylinders, sphere and disks in procedural
    // mode: the same objects, at the same depths (the facets stay within 2 mm).
    const std::string osm = tiny_roundabout_osm();
    if (!std::filesystem::exists(osm)) GTEST_SKIP() << osm << " not available";
    TempDir dir;
    const std::string scene = parse_to_scene(dir, osm);
    const std::string view = view_of_first_lamp(scene);
    ASSERT_FALSE(view.empty()) << "the extract should have street lamps";
    const Exr stored = render(dir, scene, "stored", "", 2, view);
    const Exr procedural = render(dir, scene, "procedural", "--procedural", 2, view);
    const Comparison c = compare(stored, procedural);
    EXPECT_GT(c.lamp_pixels, c.pixels / 100) << "the lamp should be in the picture";
    expect_same_picture(c);
}

TEST(ProceduralRender, SameTreesAsStored) {
    // Trees are triangles in stored mode and clipped against the same facets' planes in
    // procedural mode, with the same leaf cut-out: the same tree at the same depth (1 cm) in
    // nearly every pixel, from above a forest and from inside it.
    TempDir dir;
    const std::string scene = parse_to_scene(dir, source_path("tests/data/map_trees.osm"));
    for (const std::string& view : {std::string("--camera=-60,-150,45 --look-at=-20,-60,0 --fov 40"),
                                   std::string("--camera=-100,-60,1.7 --look-at=-80,-40,4 --fov 60")}) {
        SCOPED_TRACE(view);
        const Exr stored = render(dir, scene, "stored", "", 2, view);
        const Exr procedural = render(dir, scene, "procedural", "--procedural", 2, view);
        ASSERT_GT(stored.width, 0);
        ASSERT_EQ(stored.pixels.size(), procedural.pixels.size());
        const int kind = stored.channel("id.kind"), index = stored.channel("id.index"), depth = stored.channel("Z");
        const int pixels = stored.width * stored.height;
        int trees = 0, same_id = 0, same_depth = 0;
        float worst = 0;
        for (int p = 0; p < pixels; ++p) {
            trees += stored.at(p, kind) == 8.0f;  // ObjectKind::Tree
            if (stored.at(p, kind) != procedural.at(p, kind) || stored.at(p, index) != procedural.at(p, index)) continue;
            ++same_id;
            const float d = std::abs(stored.at(p, depth) - procedural.at(p, depth));
            same_depth += d <= 0.01f;
            worst = std::max(worst, d);
        }
        EXPECT_GT(trees, pixels / 2) << "the view should be mostly trees";
        EXPECT_GE(same_id, std::ceil(0.999 * pixels)) << pixels - same_id << " pixels differ in id";
        EXPECT_GE(same_depth, std::ceil(0.999 * pixels))
            << same_id - same_depth << " pixels with the same id differ in depth by more than 1 cm (worst " << worst
            << " m)";
    }
}

TEST(ProceduralRender, SameTerrainAsStored) {
    // A real extract on made-up hills: the stored field mesh and the procedural block walker
    // (and everything standing or draped on them) give the same ids, at the same depth (1 cm).
    const std::string osm = tiny_roundabout_osm();
    if (!std::filesystem::exists(osm)) GTEST_SKIP() << osm << " not available";
    TempDir dir;
    citygen::Scene scene = citygen::load_scene(parse_to_scene(dir, osm));
    citygen::HeightField& f = scene.terrain;
    f.cell = 4;
    f.origin = {std::floor(scene.header.bounds_min.x / 4) * 4 - 8, std::floor(scene.header.bounds_min.y / 4) * 4 - 8};
    f.nx = static_cast<uint32_t>((scene.header.bounds_max.x - f.origin.x) / 4) + 3;
    f.ny = static_cast<uint32_t>((scene.header.bounds_max.y - f.origin.y) / 4) + 3;
    for (uint32_t j = 0; j < f.ny; ++j)
        for (uint32_t i = 0; i < f.nx; ++i) {
            const double x = f.origin.x + 4.0 * i, y = f.origin.y + 4.0 * j;
            f.heights.push_back(static_cast<float>(8 + 0.06 * x + 6 * std::sin(x / 23) * std::cos(y / 31)));
        }
    const std::string hilly = dir.file("hilly.scene");
    citygen::save_scene(scene, hilly);
    const std::string view = "--camera=-150,-200,90 --look-at=0,0,5 --fov 50";
    const Exr stored = render(dir, hilly, "stored", "", 2, view);
    const Exr procedural = render(dir, hilly, "procedural", "--procedural", 2, view);
    ASSERT_GT(stored.width, 0);
    ASSERT_EQ(stored.pixels.size(), procedural.pixels.size());
    const int kind = stored.channel("id.kind"), index = stored.channel("id.index"), depth = stored.channel("Z");
    const int pixels = stored.width * stored.height;
    int terrain = 0, same_id = 0, same_depth = 0;
    for (int p = 0; p < pixels; ++p) {
        terrain += stored.at(p, kind) == 5.0f;  // ObjectKind::Terrain
        if (stored.at(p, kind) != procedural.at(p, kind) || stored.at(p, index) != procedural.at(p, index)) continue;
        ++same_id;
        same_depth += std::abs(stored.at(p, depth) - procedural.at(p, depth)) <= 0.01f;
    }
    EXPECT_GT(terrain, pixels / 20) << "the hills should show";
    EXPECT_GE(same_id, std::ceil(0.999 * pixels)) << pixels - same_id << " pixels differ in id";
    EXPECT_GE(same_depth, std::ceil(0.999 * pixels)) << same_id - same_depth << " pixels differ in depth by over 1 cm";
}

TEST(ProceduralRender, SameNightPictureAsStored) {
    // At night the picture is lamps, lit windows and their light: the same lit windows, the same
    // lamp globes and the same light samples in both modes.
    const std::string osm = tiny_roundabout_osm();
    if (!std::filesystem::exists(osm)) GTEST_SKIP() << osm << " not available";
    TempDir dir;
    const std::string scene = parse_to_scene(dir, osm);
    for (const std::string& view : {std::string("--camera=-70,-90,20 --look-at=0,0,8 --fov 45"), view_of_first_lamp(scene)}) {
        const Exr stored = render(dir, scene, "stored", "--time night", 2, view);
        const Exr procedural = render(dir, scene, "procedural", "--time night --procedural", 2, view);
        const Comparison c = compare(stored, procedural);
        SCOPED_TRACE(view);
        expect_same_picture(c);
        // Same pixels, one or two threads.
        const Exr one_thread = render(dir, scene, "one", "--time night --procedural", 1, view);
        EXPECT_TRUE(one_thread.pixels == procedural.pixels);
    }
}

TEST(NightRender, RealExtractHasLampsPoolsOfLightAndADarkSky) {
    TempDir dir;
    const std::string scene_path = parse_to_scene(dir, source_path("examples/neukolln.osm.bz2"));
    const citygen::Scene scene = citygen::load_scene(scene_path);
    ASSERT_GT(scene.lamps.size(), 10u);
    const citygen::Vec3 lamp = scene.lamps[1].position;
    const double ground = scene.ground.z + lamp.z;

    // Straight down from 50 m over a lamp: road within 4 m of a lamp's foot lies in a pool of
    // light, several times brighter than road more than 12 m from every lamp.
    char view[256];
    const citygen::Vec3 eye{lamp.x, lamp.y + 0.01, ground + 50}, target{lamp.x, lamp.y, ground};
    std::snprintf(view, sizeof view, "--camera=%.3f,%.3f,%.3f --look-at=%.3f,%.3f,%.3f --fov 70", eye.x, eye.y, eye.z,
                  target.x, target.y, target.z);
    const Exr down = render(dir, scene_path, "down", "--time night", 2, view, 8);
    ASSERT_GT(down.width, 0);
    const citygen::Camera camera = citygen::Camera::look_at(eye, target, 70, down.width, down.height);
    const int kind = down.channel("id.kind"), depth = down.channel("Z");
    double near_sum = 0, far_sum = 0;
    int near_n = 0, far_n = 0, lamp_pixels = 0;
    for (int y = 0; y < down.height; ++y) {
        for (int x = 0; x < down.width; ++x) {
            const int p = y * down.width + x;
            const float k = down.at(p, kind);
            lamp_pixels += k == 6.0f;
            if (k != 2.0f && k != 3.0f) continue;  // asphalt only (roads, joints): one albedo near and far
            const citygen::Ray ray = camera.generate_ray(x + 0.5, y + 0.5);
            const citygen::Vec3 at = ray.origin + ray.direction * down.at(p, depth);
            double nearest = 1e30;
            for (const citygen::Lamp& l : scene.lamps)
                nearest = std::min(nearest, std::hypot(at.x - l.position.x, at.y - l.position.y));
            const double luminance = 0.2126 * down.at(p, 0) + 0.7152 * down.at(p, 1) + 0.0722 * down.at(p, 2);
            if (nearest < 4) near_sum += luminance, ++near_n;
            if (nearest > 12) far_sum += luminance, ++far_n;
        }
    }
    EXPECT_GT(lamp_pixels, 0) << "the lamp seen from above";
    ASSERT_GT(near_n, 20);
    ASSERT_GT(far_n, 20);
    EXPECT_GT(near_sum / near_n, 3 * far_sum / far_n) << "pools of light under the lamps";

    // Along the street at eye height: lamps in view, and a sky far darker than the lit ground.
    const Exr street = render(dir, scene_path, "street", "--time night", 2, view_of_first_lamp(scene_path), 8);
    ASSERT_GT(street.width, 0);
    double sky_sum = 0;
    int sky_n = 0, street_lamps = 0;
    // Sky pixels away from every object's edge (a pixel's samples spread over its whole area,
    // the id is of its centre: a lit tree crown or lamp beside a sky pixel is not the sky).
    auto sky_at = [&](int x, int y) {
        return x < 0 || y < 0 || x >= street.width || y >= street.height || street.at(y * street.width + x, kind) == 0.0f;
    };
    for (int y = 0; y < street.height; ++y)
        for (int x = 0; x < street.width; ++x) {
            const int p = y * street.width + x;
            street_lamps += street.at(p, kind) == 6.0f;
            bool open_sky = true;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx) open_sky = open_sky && sky_at(x + dx, y + dy);
            if (!open_sky) continue;
            sky_sum += 0.2126 * street.at(p, 0) + 0.7152 * street.at(p, 1) + 0.0722 * street.at(p, 2);
            ++sky_n;
        }
    EXPECT_GT(street_lamps, 0);
    ASSERT_GT(sky_n, 100);
    EXPECT_LT(sky_sum / sky_n, 0.2 * near_sum / near_n) << "the night sky is dark";
    EXPECT_LT(sky_sum / sky_n, 3e-5) << "below 0.5 cd/m^2";
}
