#include "osmparse/heap/huge_page_heap.h"

#if defined(CITYGEN_TCMALLOC)

#include <sys/mman.h>

#include <cstddef>
#include <cstdint>

#include <gperftools/malloc_extension.h>

#include "common/huge_page_advice.h"

namespace citygen {

namespace {

size_t round_up(size_t n, size_t to) { return (n + to - 1) / to * to; }

// Each request rounded up to whole huge pages and aligned to one, so every page TCMalloc is given
// can be a huge page. Where mmap fails, TCMalloc's own allocator is asked instead.
class HugePageAllocator : public SysAllocator {
public:
    explicit HugePageAllocator(SysAllocator* fallback) : fallback_(fallback) {}

    void* Alloc(size_t size, size_t* actual_size, size_t alignment) override {
        if (alignment <= kHugePage && size <= (size_t{1} << 40)) {
            const size_t bytes = round_up(size, kHugePage);
            const size_t mapped = bytes + kHugePage;  // room to align the start
            void* p = mmap(nullptr, mapped, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
            if (p != MAP_FAILED) {
                const uintptr_t start = reinterpret_cast<uintptr_t>(p);
                const uintptr_t aligned = round_up(start, kHugePage);
                if (aligned > start) munmap(p, aligned - start);
                const uintptr_t end = start + mapped;
                if (end > aligned + bytes) munmap(reinterpret_cast<void*>(aligned + bytes), end - aligned - bytes);
                advise_huge_pages(reinterpret_cast<void*>(aligned), bytes);
                if (actual_size) *actual_size = bytes;
                return reinterpret_cast<void*>(aligned);
            }
        }
        return fallback_ ? fallback_->Alloc(size, actual_size, alignment) : nullptr;
    }

private:
    SysAllocator* fallback_;
};

}  // namespace

void use_huge_pages_for_the_heap() {
    MallocExtension* tcmalloc = MallocExtension::instance();
    static HugePageAllocator allocator(tcmalloc->GetSystemAllocator());
    tcmalloc->SetSystemAllocator(&allocator);
}

}  // namespace citygen

#else

namespace citygen {

void use_huge_pages_for_the_heap() {}  // glibc's malloc (or a sanitizer's) keeps its own pages

}  // namespace citygen

#endif
