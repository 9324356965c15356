// The defects of issue 8 (sanitizers, fuzzing, hostile inputs) in the renderer, one test each
// that failed before its fix; the scene model's are in tests/common/scene_io_hardening_test.cpp,
// the parser's in tests/osmparse/pipeline_hardening_test.cpp. Whole-program cases (time and
// memory limits, exit codes, nothing overwritten) are in tests/hostile/run_hostile.sh.
#include <gtest/gtest.h>

#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <random>

#include "common/error.h"
#include "render/cli_values.h"
#include "render/facade/facade.h"
#include "render/facade/facade_mesh.h"
#include "render/film/image_output.h"
#include "render/geometry/triangulate_polygon.h"
#include "render/production/memory_estimate.h"
#include "tests/test_scenes.h"
#include "tests/test_support.h"

using namespace citygen;
using namespace citygen::test;

// Defect 1: collinear or identical outline points crashed the renderer (flood_nesting).
TEST(Hardening, TriangulationOfCollinearOrIdenticalPointsIsEmpty) {
    EXPECT_TRUE(triangulate_polygon({{0, 0}, {1, 0}, {3, 0}, {2, 0}}).triangles.empty());
    EXPECT_TRUE(triangulate_polygon({{5, 5}, {5, 5}, {5, 5}, {5, 5}}).triangles.empty());
    EXPECT_TRUE(triangulate_polygon({{0, 0}, {1, 1}, {2, 2}}, {{{0, 0}, {1, 1}, {0.5, 0.5}}}).triangles.empty());
}

TEST(Hardening, CameraValuesAreBounded) {
    EXPECT_THROW(parse_point("1e308,0,0", "--camera"), Error);
    EXPECT_THROW(parse_point("0,-2e6,0", "--look-at"), Error);
    EXPECT_THROW(parse_point("nan,0,0", "--camera"), Error);
    const Vec3 p = parse_point("1,2.5,-3", "--camera");
    EXPECT_EQ(p.x, 1);
    EXPECT_EQ(p.y, 2.5);
    EXPECT_EQ(p.z, -3);
    EXPECT_THROW(check_view({1, 2, 3}, {1, 2, 3}), Error);
    EXPECT_NO_THROW(check_view({1, 2, 3}, {1, 2, 4}));
}

// Defect 3: floor and slot counts of an absurd wall overflowed int (UB; on x86 it gave a
// plain wall by accident). Now they are clamped, whatever the scene limits are.
TEST(Hardening, FacadeCellCountsOfAbsurdWallsStayInRange) {
    WallInput wall;
    wall.length = 1e12;
    wall.height = 1e12;
    const WallLayout layout = make_wall_layout(FacadeOptions{}, wall);
    EXPECT_GE(layout.floors, 1);
    EXPECT_GE(layout.slots, 1);
    EXPECT_LE(layout.floors, 1000000);
    EXPECT_LE(layout.slots, 1000000);
}

// A wall follows the ring as it is when asked (it once came from an orientation cache keyed by
// the ring's address, which a ring reversed in place fooled).
TEST(Hardening, BuildingWallFollowsTheRingItIsGiven) {
    Building b = box_building(0, 0, 10, 10);
    Vec2 p, q;
    building_wall(b, 0, &p, &q);
    EXPECT_EQ(p, Vec2(0, 0));
    EXPECT_EQ(q, Vec2(10, 0));
    std::reverse(b.outer.begin(), b.outer.end());  // now clockwise, same storage
    building_wall(b, 0, &p, &q);
    EXPECT_GT(cross(q - p, Vec2(5, 5) - p), 0);  // the building still on the left
    Vec2 p_walls, q_walls;
    BuildingWalls(b).wall(0, &p_walls, &q_walls);  // what the geometry builders use
    EXPECT_EQ(p_walls, p);
    EXPECT_EQ(q_walls, q);
}

// Defects 6 and 7: a full disk (here: a file size limit) left a truncated image in place of
// the old one and exit 0 (PNG), or a temporary file and libjpeg's own line (JPEG).
TEST(Hardening, ImageWriteErrorsKeepTheOldFile) {
    for (const char* name : {"out.png", "out.jpg", "out.exr"}) {
        TempDir dir;
        const std::string path = dir.file(name);
        write_text(path, "old image");
        const pid_t child = ::fork();
        ASSERT_GE(child, 0);
        if (child == 0) {
            ::signal(SIGXFSZ, SIG_IGN);  // writes past the limit fail with EFBIG instead
            const rlimit limit{2000, 2000};
            ::setrlimit(RLIMIT_FSIZE, &limit);
            Film film;
            film.width = film.height = 128;
            std::mt19937 rng(1);
            for (int i = 0; i < 3 * 128 * 128; ++i) film.rgb.push_back(std::uniform_real_distribution<float>(0, 1)(rng));
            try {
                write_image(film, path, 1.0);
            } catch (const Error&) {
                ::_exit(3);
            }
            ::_exit(0);
        }
        int status = 0;
        ::waitpid(child, &status, 0);
        EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 3) << name << ": the write error went unnoticed";
        EXPECT_EQ(read_text(path), "old image") << name;
        size_t files = 0;
        for ([[maybe_unused]] const auto& entry : std::filesystem::directory_iterator(dir.path())) ++files;
        EXPECT_EQ(files, 1u) << name << ": a temporary file was left behind";
    }
}

// Defect 4: a render that cannot fit is refused with its size before anything is built.
TEST(Hardening, MemoryEstimateGrowsWithGeometryAndRefusesWhatCannotFit) {
    const FacadeOptions facades;
    RenderSettings settings;
    const GeometryModes stored = GeometryModes::all(GeometryMode::Stored);
    const double low = estimate_render_memory(scene_with(box_building(0, 0, 100, 100, 10)), stored, facades, settings).bytes;
    const MemoryEstimate tall =
        estimate_render_memory(scene_with(box_building(0, 0, 9000, 9000, 1000)), stored, facades, settings);
    EXPECT_GT(tall.stored_triangles, 1e8);
    EXPECT_GT(tall.bytes, 100 * low);
    const double procedural = estimate_render_memory(scene_with(box_building(0, 0, 9000, 9000, 1000)),
                                                     GeometryModes::all(GeometryMode::Procedural), facades, settings)
                                  .bytes;
    EXPECT_LT(procedural, 2 * low);
    EXPECT_GT(available_memory_bytes(), 0);
    MemoryEstimate absurd;
    absurd.bytes = 1e18;
    try {
        check_memory_fits(absurd);
        FAIL() << "an exabyte fitted";
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("needs about"), std::string::npos) << e.what();
    }
}

TEST(Hardening, WallTriangleEstimateIsExact) {
    int walls = 0;
    for (uint64_t seed = 0; seed < 40; ++seed)
        for (double height : {2.0, 4.0, 9.0, 31.0, 120.0})
            for (double length : {1.0, 3.0, 7.5, 26.0, 140.0}) {
                FacadeOptions options;
                options.seed = seed;
                options.shop_probability = 0.5;
                WallInput wall;
                wall.building_key = seed * 7919;
                wall.length = length;
                wall.height = height;
                const WallLayout layout = make_wall_layout(options, wall);
                ASSERT_EQ(wall_triangle_estimate(layout), static_cast<double>(wall_triangle_count(layout)))
                    << "seed " << seed << " height " << height << " length " << length;
                walls += !layout.plain();
            }
    EXPECT_GT(walls, 300);
}
