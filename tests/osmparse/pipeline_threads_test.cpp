// --threads: the scene and the report's rows are the same whatever the number of threads the
// stages after reading run on (build_buildings in parallel, roofs beside the last stages).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "common/scene_io.h"
#include "osmparse/pipeline.h"

using namespace citygen;

namespace {

struct Parsed {
    std::vector<uint8_t> scene;
    std::string report_rows;  // the printed report without the stage times
};

Parsed parse_with_threads(const std::string& input, int threads) {
    ParseJob job;
    job.input = input;
    job.quiet = true;
    job.threads = threads;
    ParseReport report;
    Parsed out;
    out.scene = encode_scene(parse_osm_to_scene(job, report));
    char* text = nullptr;
    size_t size = 0;
    std::FILE* memory = open_memstream(&text, &size);
    report.print(memory);
    std::fclose(memory);
    out.report_rows = std::string(text, size);
    std::free(text);
    out.report_rows = out.report_rows.substr(0, out.report_rows.find("\nstage "));
    return out;
}

void expect_same_with_one_and_two_threads(const std::string& input) {
    const Parsed one = parse_with_threads(input, 1);
    const Parsed two = parse_with_threads(input, 2);
    EXPECT_GT(one.scene.size(), 1000u);
    EXPECT_TRUE(one.scene == two.scene) << input << ": scenes differ between --threads 1 and 2";
    EXPECT_EQ(one.report_rows, two.report_rows);
    EXPECT_NE(one.report_rows.find("buildings"), std::string::npos);
}

}  // namespace

TEST(Threads, OneAndTwoThreadsGiveTheSameSceneOnAFixture) {
    expect_same_with_one_and_two_threads(std::string(CITYGEN_SOURCE_DIR) + "/tests/data/road_brushing_building.osm");
}

TEST(Threads, OneAndTwoThreadsGiveTheSameSceneOnMonaco) {
    const std::string monaco = std::string(CITYGEN_SHARED_DATA_DIR) + "/monaco.osm.pbf";
    if (!std::filesystem::exists(monaco)) GTEST_SKIP() << "no Monaco extract at " << monaco;
    expect_same_with_one_and_two_threads(monaco);
}

// osmparse writes its file part by part (parse_osm_to_file): the bytes of encode_scene of the
// whole scene, with and without the empty blocks' buildings, on one and two threads.
TEST(Threads, WritingPartByPartGivesTheSameBytes) {
    const std::string input = std::string(CITYGEN_SOURCE_DIR) + "/tests/data/empty_block.osm";
    for (const bool blocks : {false, true})
        for (const int threads : {1, 2}) {
            ParseJob job;
            job.input = input;
            job.quiet = true;
            job.threads = threads;
            job.params.blocks.enabled = blocks;
            ParseReport report, file_report;
            const std::vector<uint8_t> whole = encode_scene(parse_osm_to_scene(job, report));
            const std::string path = ::testing::TempDir() + "part_by_part.scene";
            parse_osm_to_file(job, file_report, path);
            std::FILE* f = std::fopen(path.c_str(), "rb");
            ASSERT_NE(f, nullptr);
            std::vector<uint8_t> written(whole.size() + 1);
            written.resize(std::fread(written.data(), 1, written.size(), f));
            std::fclose(f);
            std::remove(path.c_str());
            EXPECT_GT(whole.size(), 1000u);
            EXPECT_TRUE(written == whole) << "blocks " << blocks << ", threads " << threads;
        }
}
