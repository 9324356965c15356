// Transparent huge pages, which most systems grant only where asked
// (/sys/kernel/mm/transparent_hugepage/enabled is "madvise"). Both programs fill tens of
// megabytes to gigabytes of fresh memory; in 4 KiB pages the kernel zeroes each on its first
// touch, and what is read at random (a render's vertices and indices) misses the TLB.
#pragma once

#include <cstddef>

namespace citygen {

constexpr size_t kHugePage = size_t{2} << 20;

// Asks the kernel to back the whole huge pages within [data, data + bytes) with huge pages. A
// hint: where it is refused the memory stays in small pages.
void advise_huge_pages(const void* data, size_t bytes);

}  // namespace citygen
