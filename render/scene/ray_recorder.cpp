#include "render/scene/ray_recorder.h"

namespace citygen {

std::vector<std::vector<RecordedRay>> RayRecorder::thread_lists() const {
    std::vector<std::vector<RecordedRay>> lists;
    for (const auto& list : lists_)
        if (!list.empty()) lists.push_back(list);
    return lists;
}

uint64_t RayRecorder::count() const {
    uint64_t total = 0;
    for (const auto& list : lists_) total += list.size();
    return total;
}

uint64_t RayRecorder::count(RayKind kind) const {
    uint64_t total = 0;
    for (const auto& list : lists_)
        for (const RecordedRay& ray : list) total += ray.kind == kind;
    return total;
}

}  // namespace citygen
