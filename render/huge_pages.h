// Large scenes in 2 MiB pages. A metropolis's set-up fills gigabytes of fresh memory, and the
// kernel hands it over 4 KiB at a time unless malloc asks for transparent huge pages. glibc asks
// only when its `glibc.malloc.hugetlb` tunable is set, and it reads tunables when a program
// starts, so the render starts itself again with the tunable set (huge_page_tunables says what
// else it sets, and why).
#pragma once

#include <string>
#include <vector>

namespace citygen {

// Scenes of at least this many bytes together are worth the second start-up (render's
// libraries take a fraction of a second to load): their set-up saves seconds per 100 MB.
constexpr unsigned long long kHugePageSceneBytes = 64ull << 20;

// Whether a render of these scenes restarts: they are that large and `tunables` (the value of
// GLIBC_TUNABLES, or null) does not set the tunable yet (by us or by the user).
bool wants_huge_pages(const std::vector<std::string>& scene_paths, const char* tunables);

// The value of GLIBC_TUNABLES for the restart: `tunables` (the current value, or null) with
// huge pages and the heap settings that go with them, each unless it is set already.
std::string huge_page_tunables(const char* tunables);

// Replaces the process by the same command with the tunable set where malloc is glibc's and
// wants_huge_pages. Returns when it does not restart, or when the restart fails (the render then
// runs as it would have, in 4 KiB pages).
void restart_with_huge_pages_for(const std::vector<std::string>& scene_paths, char** argv);

}  // namespace citygen
