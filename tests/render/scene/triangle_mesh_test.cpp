// A stored mesh's buffers, reserved once, are marked for huge pages: the mapping that holds them
// carries the kernel's "hg" flag (MADV_HUGEPAGE), whether or not huge pages are free right now.
#include <cstdint>
#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "common/huge_page_advice.h"
#include "render/scene/triangle_mesh.h"

using namespace citygen;

namespace {

// The VmFlags line of the mapping in /proc/self/smaps that holds `address`, or "" if none does.
std::string vm_flags_at(const void* address) {
    const auto at = reinterpret_cast<uintptr_t>(address);
    std::ifstream smaps("/proc/self/smaps");
    std::string line;
    bool inside = false;
    while (std::getline(smaps, line)) {
        uintptr_t begin = 0, end = 0;
        char dash = 0;
        std::istringstream range(line);
        if (range >> std::hex >> begin >> dash >> end && dash == '-' && line.find(':') > line.find(' ')) {
            inside = begin <= at && at < end;
            continue;
        }
        if (inside && line.rfind("VmFlags:", 0) == 0) return line;
    }
    return "";
}

bool marked_for_huge_pages(const void* address) { return vm_flags_at(address).find(" hg") != std::string::npos; }

const void* first_whole_huge_page(const void* data) {
    return reinterpret_cast<const void*>((reinterpret_cast<uintptr_t>(data) + kHugePage - 1) & ~(kHugePage - 1));
}

TEST(TriangleMesh, LargeBuffersAreMarkedForHugePages) {
    TriangleMesh mesh;
    if (vm_flags_at(&mesh).empty()) GTEST_SKIP() << "no /proc/self/smaps with VmFlags here";
    if (!std::ifstream("/sys/kernel/mm/transparent_hugepage/enabled")) GTEST_SKIP() << "a kernel without huge pages";
    mesh.reserve(2'000'000, 2'000'000);  // 24 MB of vertices, 24 MB of indices
    EXPECT_TRUE(marked_for_huge_pages(first_whole_huge_page(mesh.vertices.data())));
    EXPECT_TRUE(marked_for_huge_pages(first_whole_huge_page(mesh.indices.data())));
    EXPECT_TRUE(marked_for_huge_pages(first_whole_huge_page(mesh.face_object.data())));
    EXPECT_GE(mesh.vertices.capacity(), 3 * 2'000'000u + 4);  // Embree's padding
    EXPECT_GE(mesh.face_material.capacity(), 2'000'000u);
    // A buffer that spans no whole huge page is left as it is.
    TriangleMesh small;
    small.reserve(1000, 1000);
    EXPECT_FALSE(marked_for_huge_pages(small.vertices.data()));
}

}  // namespace
