// A record of every ray a render traces, for tests/bench/ray_limit: the bench replays the same
// rays through Embree with no shading to see how close the render comes to Embree's own speed.
// RenderScene records only while a recorder is attached (RenderScene::set_ray_recorder); with
// none attached a ray costs one test of a null pointer.
#pragma once

#include <cstdint>
#include <vector>

#include <tbb/enumerable_thread_specific.h>

#include "render/scene/hit.h"

namespace citygen {

// Camera: the first ray of a path. Bounce: any other closest-hit ray (later path segments, rays
// to small globes). Shadow: any-hit rays (RenderScene::occluded).
enum class RayKind : uint8_t { Camera, Bounce, Shadow };
constexpr int kRayKindCount = 3;

// A ray as Embree received it (single precision) and whether it hit something.
struct RecordedRay {
    float origin[3];
    float direction[3];
    float tnear, tfar;
    RayKind kind;
    bool hit;
};

class RayRecorder {
public:
    // Thread-safe: each thread appends to a list of its own, in the order it traced the rays.
    void record(const RecordedRay& ray) { lists_.local().push_back(ray); }

    // The rays, one list per thread that traced any (each in its own order).
    std::vector<std::vector<RecordedRay>> thread_lists() const;
    uint64_t count() const;
    uint64_t count(RayKind kind) const;
    void clear() { lists_.clear(); }

private:
    tbb::enumerable_thread_specific<std::vector<RecordedRay>> lists_;
};

}  // namespace citygen
