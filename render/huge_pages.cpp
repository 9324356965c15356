#include "render/huge_pages.h"

#include <cstdlib>
#include <cstring>
#include <sys/stat.h>
#include <unistd.h>

namespace citygen {

bool wants_huge_pages(const std::vector<std::string>& scene_paths, const char* tunables) {
    if (tunables && std::strstr(tunables, "glibc.malloc.hugetlb")) return false;
    unsigned long long bytes = 0;
    for (const std::string& path : scene_paths) {
        struct stat info;
        if (::stat(path.c_str(), &info) == 0 && S_ISREG(info.st_mode)) bytes += info.st_size;
    }
    return bytes >= kHugePageSceneBytes;
}

std::string huge_page_tunables(const char* tunables) {
    // The tunable alone also pads each growth of malloc's heaps to whole huge pages, which
    // raised the peak above that of small pages; without the pad it is no higher, and the
    // set-up as fast (docs/bench/2026-12-scale.md, sixth round). The set-up also frees hundreds
    // of megabytes (the light tree's build arrays, the loader's buffers) just before it needs as
    // much again: kept in malloc's heap rather than given back (no mapping of its own for a large
    // block, no trimming), they are reused without the kernel zeroing fresh pages (twelfth round).
    std::string value = tunables && *tunables ? std::string(tunables) + ":" : std::string();
    value += "glibc.malloc.hugetlb=1";
    for (const char* tunable : {"glibc.malloc.top_pad=0", "glibc.malloc.mmap_max=0",
                                "glibc.malloc.trim_threshold=4611686018427387904"}) {
        const std::string name(tunable, std::strchr(tunable, '=') + 1);
        if (value.find(name) == std::string::npos) value += std::string(":") + tunable;  // the user's own stays
    }
    return value;
}

void restart_with_huge_pages_for(const std::vector<std::string>& scene_paths, char** argv) {
#if defined(__GLIBC__) && defined(__linux__)
    const char* tunables = std::getenv("GLIBC_TUNABLES");
    if (!wants_huge_pages(scene_paths, tunables)) return;
    if (::setenv("GLIBC_TUNABLES", huge_page_tunables(tunables).c_str(), 1) != 0) return;
    ::execv("/proc/self/exe", argv);
    // Not restarted: the same render, in small pages.
#else
    (void)scene_paths;
    (void)argv;
#endif
}

}  // namespace citygen
