// TCMalloc's heap in 2 MiB pages. A parse fills tens of megabytes to gigabytes of fresh memory,
// and the kernel hands it over 4 KiB at a time, zeroing each page on its first touch, unless the
// memory is marked for transparent huge pages (which most systems grant only where asked:
// /sys/kernel/mm/transparent_hugepage/enabled is "madvise").
#pragma once

namespace citygen {

// From now on, the memory TCMalloc takes from the system comes in 2 MiB-aligned runs marked for
// huge pages. Call once, early in main. Does nothing where osmparse is built without TCMalloc.
void use_huge_pages_for_the_heap();

}  // namespace citygen
