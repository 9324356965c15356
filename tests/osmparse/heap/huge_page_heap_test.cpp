#include "osmparse/heap/huge_page_heap.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdio>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace citygen {
namespace {

struct Mapping {
    uintptr_t start = 0, end = 0;
    bool marked_for_huge_pages = false;  // VmFlags "hg": madvise(MADV_HUGEPAGE)
};

// The mapping of this process that holds p, from /proc/self/smaps.
Mapping mapping_holding(const void* p) {
    const uintptr_t at = reinterpret_cast<uintptr_t>(p);
    std::ifstream smaps("/proc/self/smaps");
    std::string line;
    Mapping current, found;
    while (std::getline(smaps, line)) {
        unsigned long start, end;
        if (std::sscanf(line.c_str(), "%lx-%lx ", &start, &end) == 2 && line.find(':') > line.find(' ')) {
            current = {start, end, false};
        } else if (line.rfind("VmFlags:", 0) == 0) {
            std::istringstream flags(line.substr(8));
            std::string flag;
            while (flags >> flag) current.marked_for_huge_pages |= flag == "hg";
            if (current.start <= at && at < current.end) found = current;
        }
    }
    return found;
}

// The heap's memory taken from the system after the call comes in 2 MiB-aligned mappings marked
// for huge pages (the parse's first touches then cost one fault per 2 MiB, not per 4 KiB).
TEST(HugePageHeap, NewHeapMemoryIsMarkedForHugePages) {
#if !defined(CITYGEN_TCMALLOC)
    GTEST_SKIP() << "built without TCMalloc: the heap is glibc's (or a sanitizer's)";
#endif
    if (!std::ifstream("/sys/kernel/mm/transparent_hugepage/enabled"))
        GTEST_SKIP() << "this kernel has no transparent huge pages";
    use_huge_pages_for_the_heap();
    // More than any free memory the heap held before: the last blocks come from the system.
    std::vector<std::unique_ptr<char[]>> blocks;
    for (int i = 0; i < 32; ++i) {
        blocks.emplace_back(new char[8 << 20]);  // not zeroed: only the first byte is touched
        blocks.back()[0] = 1;
    }
    const Mapping m = mapping_holding(blocks.back().get());
    ASSERT_NE(m.end, 0u) << "no mapping holds the block";
    EXPECT_TRUE(m.marked_for_huge_pages);
    EXPECT_EQ(m.start % (2u << 20), 0u);
}

}  // namespace
}  // namespace citygen
