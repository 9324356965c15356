// The image loop: the same seed gives the same pixels whatever the thread count.
#include <cstring>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "render/film/render_image.h"
#include "render/geometry/build_render_scene.h"
#include "tests/render/small_town.h"

using namespace citygen;
using namespace citygen::test;

TEST(Determinism, SameSeedGivesIdenticalPixelsWithOneOrTwoThreads) {
    const auto scene = build_render_scene(small_town(), GeometryModes{});
    const MaterialTable materials = default_materials();
    const Sky sky = Sky::daylight(TimeOfDay::Sunset);
    RenderSettings r = tiny(4);
    r.width = 40;  // several tiles
    r.height = 36;
    r.integrator = IntegratorSettings{};
    const PathContext context{*scene, materials, sky, r.integrator};
    Film one, two;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = render_image(context, view_of_town(r), r);
    }
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
        two = render_image(context, view_of_town(r), r);
    }
    ASSERT_EQ(one.rgb.size(), two.rgb.size());
    EXPECT_EQ(0, std::memcmp(one.rgb.data(), two.rgb.data(), one.rgb.size() * sizeof(float)));
    r.seed = 2;
    const Film other_seed = render_image(context, view_of_town(r), r);
    EXPECT_NE(0, std::memcmp(one.rgb.data(), other_seed.rgb.data(), one.rgb.size() * sizeof(float)));
}
