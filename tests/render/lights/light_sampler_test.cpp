#include "render/lights/light_sampler.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <vector>

#include <tbb/task_arena.h>

namespace citygen {
namespace {

// Window-strip-like lights: small boxes facing one of many wall directions, and lamp globes.
std::vector<LightBounds> city_of_lights(size_t count) {
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> unit(0, 1);
    std::vector<LightBounds> lights(count);
    for (size_t i = 0; i < count; ++i) {
        const Vec3 c{2000 * unit(rng), 2000 * unit(rng), 30 * unit(rng)};
        LightBounds& b = lights[i];
        b.set_box(c - Vec3{1, 1, 0.5}, c + Vec3{1, 1, 0.5});
        b.phi = static_cast<float>(0.1 + unit(rng));
        if (i % 5 == 0) {
            b.cos_theta_o = -1;  // a globe
        } else {
            const double a = 2 * 3.14159265358979 * std::floor(16 * unit(rng)) / 16;  // 16 wall directions
            b.set_axis({std::cos(a), std::sin(a), 0});
            b.cos_theta_o = 1;
            b.cos_theta_e = 0;
        }
    }
    return lights;
}

std::unique_ptr<LightSampler> tree_with_threads(const std::vector<LightBounds>& lights, int threads) {
    tbb::task_arena arena(threads);
    std::unique_ptr<LightSampler> sampler;
    arena.execute([&] { sampler = make_light_sampler(lights, LightSamplerKind::Tree); });
    return sampler;
}

// Large enough that the build splits its nodes across threads (kParallelItems).
TEST(BVHLightSampler, SameTreeWithOneThreadAndWithMany) {
    const std::vector<LightBounds> lights = city_of_lights(30000);
    const auto one = tree_with_threads(lights, 1);
    const auto many = tree_with_threads(lights, 2);
    EXPECT_EQ(one->bytes(), many->bytes());
    std::mt19937_64 rng(11);
    std::uniform_real_distribution<double> unit(0, 1);
    int sampled = 0;
    for (int q = 0; q < 2000; ++q) {
        const Vec3 p{2000 * unit(rng), 2000 * unit(rng), 1.5};
        const Vec3 n = q % 2 ? Vec3{0, 0, 1} : Vec3{1, 0, 0};
        const double u = unit(rng);
        uint32_t light_one = 0, light_many = 0;
        double pmf_one = 0, pmf_many = 0;
        const bool ok_one = one->sample(p, n, u, &light_one, &pmf_one);
        const bool ok_many = many->sample(p, n, u, &light_many, &pmf_many);
        ASSERT_EQ(ok_one, ok_many);
        if (!ok_one) continue;
        ++sampled;
        EXPECT_EQ(light_one, light_many);
        EXPECT_EQ(pmf_one, pmf_many);  // bit for bit: the same tree, not a similar one
        const uint32_t other = static_cast<uint32_t>(q * 13 % lights.size());
        EXPECT_EQ(one->pmf(p, n, other), many->pmf(p, n, other));
    }
    EXPECT_GT(sampled, 1900);
}

// A tree built in parallel is a whole tree: every light reachable, the probabilities a distribution.
TEST(BVHLightSampler, ProbabilitiesOfALargeTreeSumToOne) {
    const std::vector<LightBounds> lights = city_of_lights(20000);
    const auto tree = tree_with_threads(lights, 2);
    for (const Vec3 p : {Vec3{1000, 1000, 1.5}, Vec3{10, 1990, 20}}) {
        double sum = 0;
        for (uint32_t i = 0; i < lights.size(); ++i) sum += tree->pmf(p, {0, 0, 0}, i);
        EXPECT_NEAR(sum, 1.0, 1e-6);
    }
}

// The nodes' cones hold their lights' normals (the split search's cheaper bucket cones never
// become a node's), and every leaf is where the tree says: a light that surely reaches a point
// has a chance there, and sampling it reports the probability pmf() gives.
TEST(BVHLightSampler, EveryLightThatReachesAPointHasAChance) {
    const std::vector<LightBounds> lights = city_of_lights(20000);
    const auto tree = tree_with_threads(lights, 2);
    for (const Vec3 p : {Vec3{1000, 1000, 1.5}, Vec3{10, 1990, 20}, Vec3{1500, 300, 60}}) {
        int reaching = 0;
        for (uint32_t i = 0; i < lights.size(); ++i) {
            const LightBounds& b = lights[i];
            // A globe lights every way; a pane lights p if p is in front of all of its box (the
            // box reaches at most 1.5 m along its normal from the centre).
            const bool reaches = b.cos_theta_o <= -1 || dot(p - b.centroid(), b.axis()) > 1.5;
            if (!reaches) continue;
            ++reaching;
            EXPECT_GT(tree->pmf(p, {0, 0, 0}, i), 0) << "light " << i;
        }
        EXPECT_GT(reaching, 10000);
        std::mt19937_64 rng(3);
        std::uniform_real_distribution<double> unit(0, 1);
        for (int s = 0; s < 200; ++s) {
            uint32_t light = 0;
            double pmf = 0;
            ASSERT_TRUE(tree->sample(p, {0, 0, 0}, unit(rng), &light, &pmf));
            EXPECT_DOUBLE_EQ(pmf, tree->pmf(p, {0, 0, 0}, light));
        }
    }
}

// Two equal globes, 10 m and 200 m from a point: by power over squared distance alone the far one
// would have (10 / 200)^2 of the near one's chance; the visibility prior (LightBounds4::kReach)
// gives it far less, and still some.
TEST(BVHLightSampler, AFarLightHasLessChanceThanItsSquaredDistanceGives) {
    std::vector<LightBounds> lights(2);
    const Vec3 p{0, 0, 2};
    const double distance[2] = {10, 200};
    for (int i = 0; i < 2; ++i) {
        const Vec3 c{distance[i], 0, 2};
        lights[i].set_box(c - Vec3{0.01, 0.01, 0.01}, c + Vec3{0.01, 0.01, 0.01});
        lights[i].phi = 1;
        lights[i].cos_theta_o = -1;
    }
    const auto tree = make_light_sampler(lights, LightSamplerKind::Tree);
    const double near = tree->pmf(p, {0, 0, 0}, 0), far = tree->pmf(p, {0, 0, 0}, 1);
    EXPECT_NEAR(near + far, 1, 1e-9);
    EXPECT_GT(far, 0);
    EXPECT_LT(far / near, 0.5 * (10.0 / 200) * (10.0 / 200));
}

}  // namespace
}  // namespace citygen
