// The ray recorder of tests/bench/ray_limit: it sees every ray a render traces, labels them,
// keeps them as Embree got them, and costs nothing once detached.
#include <gtest/gtest.h>

#include "render/film/render_image.h"
#include "render/geometry/build_render_scene.h"
#include "render/scene/ray_recorder.h"
#include "tests/render/small_town.h"

using namespace citygen;
using namespace citygen::test;

namespace {

RenderSettings small_render() {
    RenderSettings r = tiny(3);
    r.integrator = IntegratorSettings{};  // the render's own depth and roulette
    return r;
}

Ray ray_of(const RecordedRay& recorded) {
    const float* o = recorded.origin;
    const float* d = recorded.direction;
    return Ray{{o[0], o[1], o[2]}, {d[0], d[1], d[2]}, recorded.tnear, recorded.tfar};
}

}  // namespace

TEST(RayRecorder, RecordsEveryRayOfARenderWithOneCameraRayPerSample) {
    const auto scene = build_render_scene(small_town(), GeometryModes{});
    const MaterialTable materials = default_materials();
    const Sky sky = Sky::daylight(TimeOfDay::Day);
    const RenderSettings r = small_render();
    RayRecorder recorder;
    scene->set_ray_recorder(&recorder);
    RenderStats stats;
    render_image({*scene, materials, sky, r.integrator}, view_of_town(r), r, &stats);
    scene->set_ray_recorder(nullptr);
    EXPECT_EQ(recorder.count(RayKind::Camera), uint64_t(r.width) * r.height * r.spp);
    EXPECT_GT(recorder.count(RayKind::Bounce), 0u);
    EXPECT_GT(recorder.count(RayKind::Shadow), 0u);
    EXPECT_EQ(recorder.count(), stats.rays);  // the render's own count of traced rays

    const uint64_t before = recorder.count();
    render_image({*scene, materials, sky, r.integrator}, view_of_town(r), r);
    EXPECT_EQ(recorder.count(), before);  // detached: nothing more
}

TEST(RayRecorder, ARecordedRayTracedAgainHitsWhatItHit) {
    const auto scene = build_render_scene(small_town(), GeometryModes{});
    const MaterialTable materials = default_materials();
    const Sky sky = Sky::daylight(TimeOfDay::Day);
    const RenderSettings r = small_render();
    RayRecorder recorder;
    scene->set_ray_recorder(&recorder);
    render_image({*scene, materials, sky, r.integrator}, view_of_town(r), r);
    scene->set_ray_recorder(nullptr);
    uint64_t hits = 0, misses = 0;
    for (const auto& list : recorder.thread_lists())
        for (const RecordedRay& recorded : list) {
            Hit hit;
            const bool found = recorded.kind == RayKind::Shadow ? scene->occluded(ray_of(recorded))
                                                                : scene->intersect(ray_of(recorded), hit);
            ASSERT_EQ(found, recorded.hit);
            (found ? hits : misses) += 1;
        }
    EXPECT_GT(hits, 0u);
    EXPECT_GT(misses, 0u);
}
