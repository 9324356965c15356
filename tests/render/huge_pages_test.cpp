#include "render/huge_pages.h"

#include <filesystem>

#include <gtest/gtest.h>

#include "tests/test_support.h"

namespace citygen {
namespace {

using namespace test;

// A file of `bytes` zeros that takes no disk space.
std::string sparse_file(const TempDir& dir, const std::string& name, unsigned long long bytes) {
    const std::string path = dir.file(name);
    write_text(path, "");
    std::filesystem::resize_file(path, bytes);
    return path;
}

TEST(HugePages, OnlyScenesThatLargeRestart) {
    TempDir dir;
    const std::string small = sparse_file(dir, "small.scene", kHugePageSceneBytes - 1);
    const std::string large = sparse_file(dir, "large.scene", kHugePageSceneBytes);
    EXPECT_FALSE(wants_huge_pages({small}, nullptr));
    EXPECT_TRUE(wants_huge_pages({large}, nullptr));
    // Tiles count together.
    const std::string half = sparse_file(dir, "half.scene", kHugePageSceneBytes / 2);
    EXPECT_TRUE(wants_huge_pages({half, half}, nullptr));
    // What is not a readable file counts for nothing (the loader refuses it later).
    EXPECT_FALSE(wants_huge_pages({dir.path(), dir.file("missing.scene")}, nullptr));
}

TEST(HugePages, TheTunableSetByAnyoneStopsTheRestart) {
    TempDir dir;
    const std::string large = sparse_file(dir, "large.scene", kHugePageSceneBytes);
    EXPECT_FALSE(wants_huge_pages({large}, "glibc.malloc.hugetlb=1"));  // the restarted render
    EXPECT_FALSE(wants_huge_pages({large}, "glibc.malloc.hugetlb=0"));  // the user said no
    EXPECT_TRUE(wants_huge_pages({large}, "glibc.malloc.arena_max=2"));
    EXPECT_TRUE(wants_huge_pages({large}, ""));
}

TEST(HugePages, TheRestartKeepsFreedMemoryInTheHeapAndTheUsersOwnSettings) {
    EXPECT_EQ(huge_page_tunables(nullptr),
              "glibc.malloc.hugetlb=1:glibc.malloc.top_pad=0:glibc.malloc.mmap_max=0:"
              "glibc.malloc.trim_threshold=4611686018427387904");
    EXPECT_EQ(huge_page_tunables(""), huge_page_tunables(nullptr));
    const std::string value = huge_page_tunables("glibc.malloc.arena_max=2:glibc.malloc.mmap_max=8");
    EXPECT_EQ(value.find("glibc.malloc.arena_max=2:glibc.malloc.mmap_max=8:glibc.malloc.hugetlb=1"), 0u) << value;
    EXPECT_EQ(value.find("mmap_max=0"), std::string::npos) << value;  // the user's value stays
    EXPECT_NE(value.find("glibc.malloc.trim_threshold="), std::string::npos) << value;
}

TEST(HugePages, ALargeBadSceneStillGivesOneLine) {
    // The restarted render reports the bad file once, as the first start would have.
    TempDir dir;
    const std::string large = sparse_file(dir, "large.scene", kHugePageSceneBytes);
    const CommandResult r = render(quoted(large) + " -o " + quoted(dir.file("out.png")) + " --quiet");
    EXPECT_EQ(r.exit_code, 1);
    EXPECT_EQ(count_lines(r.err), 1) << r.err;
    EXPECT_NE(r.err.find("not a citygen scene"), std::string::npos) << r.err;
    EXPECT_FALSE(std::filesystem::exists(dir.file("out.png")));
}

}  // namespace
}  // namespace citygen
