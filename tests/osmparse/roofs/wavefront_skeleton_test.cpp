// The double-precision wavefront skeleton (osmparse/roofs/wavefront_skeleton.h) gives CGAL's faces,
// in CGAL's order, whenever it answers; it declines the ties only exact arithmetic can decide.
#include <gtest/gtest.h>

#include <cmath>

#include "common/rng.h"
#include "osmparse/roofs/roof_skeleton.h"
#include "osmparse/roofs/wavefront_skeleton.h"

namespace citygen {
namespace {

// True when the wavefront answered; then its faces must equal CGAL's within `tolerance`.
bool agrees_with_cgal(const Ring& ring, double tolerance = 1e-6) {
    std::vector<SkeletonFace> fast, exact;
    if (!wavefront_skeleton_faces(ring, &fast)) {
        EXPECT_TRUE(fast.empty());
        return false;
    }
    EXPECT_TRUE(straight_skeleton_faces(ring, {}, &exact));
    EXPECT_EQ(fast.size(), exact.size());
    for (size_t i = 0; i < std::min(fast.size(), exact.size()); ++i) {
        EXPECT_EQ(fast[i].points.size(), exact[i].points.size()) << "face " << i;
        if (fast[i].points.size() != exact[i].points.size()) continue;
        for (size_t j = 0; j < fast[i].points.size(); ++j) {
            EXPECT_LE(length(fast[i].points[j] - exact[i].points[j]), tolerance) << "face " << i << " point " << j;
            EXPECT_NEAR(fast[i].times[j], exact[i].times[j], tolerance) << "face " << i << " point " << j;
        }
    }
    return true;
}

// An orthogonal outline (L, T, U, ...) with every point moved by up to `jitter` metres, far
// from the origin as projected city coordinates are.
Ring jittered(const Ring& shape, double jitter, uint64_t seed) {
    Ring out;
    for (size_t i = 0; i < shape.size(); ++i) {
        const double dx = jitter * (2 * hash_to_unit(hash_keys(seed, i, 1)) - 1);
        const double dy = jitter * (2 * hash_to_unit(hash_keys(seed, i, 2)) - 1);
        out.push_back({shape[i].x + dx + 3512.25, shape[i].y + dy - 1780.5});
    }
    return out;
}

const std::vector<Ring> kShapes = {
    {{0, 0}, {20, 0}, {20, 8}, {8, 8}, {8, 20}, {0, 20}},                              // L
    {{0, 0}, {30, 0}, {30, 8}, {19, 8}, {19, 22}, {11, 22}, {11, 8}, {0, 8}},          // T
    {{0, 0}, {30, 0}, {30, 20}, {22, 20}, {22, 7}, {8, 7}, {8, 20}, {0, 20}},          // U
    {{0, 0}, {14, 0}, {14, 9}, {25, 9}, {25, 18}, {6, 18}, {6, 9}, {0, 9}},            // Z-ish
    {{0, 0}, {40, 0}, {40, 10}, {30, 10}, {30, 25}, {22, 25}, {22, 10}, {10, 10},
     {10, 18}, {0, 18}},                                                                // E-ish
};

TEST(WavefrontSkeleton, EqualsCgalOnBentFootprints) {
    int answered = 0, total = 0;
    for (const Ring& shape : kShapes)
        for (uint64_t seed = 1; seed <= 40; ++seed) {
            ++total;
            answered += agrees_with_cgal(jittered(shape, 0.3, seed));
        }
    // Jittered outlines have no exact ties: nearly all are answered without CGAL.
    EXPECT_GE(answered, total * 9 / 10) << answered << " of " << total;
}

TEST(WavefrontSkeleton, EqualsCgalOnStarShapes) {
    // Many reflex corners at once: split events one after another in several wavefront pieces.
    int answered = 0, total = 0;
    for (uint64_t seed = 1; seed <= 60; ++seed) {
        const int n = 8 + static_cast<int>(seed % 17);
        Ring star;
        for (int i = 0; i < n; ++i) {
            const double angle = 2 * kPi * (i + 0.4 * hash_to_unit(hash_keys(seed, i, 3))) / n;
            const double radius = 10 + 25 * hash_to_unit(hash_keys(seed, i, 4));
            star.push_back({radius * std::cos(angle) - 812.5, radius * std::sin(angle) + 2230.75});
        }
        ++total;
        answered += agrees_with_cgal(star);
    }
    EXPECT_GE(answered, total * 9 / 10) << answered << " of " << total;
}

TEST(WavefrontSkeleton, ExactTiesGoToCgal) {
    // A square-armed L: both arm ends and the corner meet at once; a plus sign: four reflex
    // corners at one time. The wavefront may decline these; if it answers, it must be right.
    const Ring plus{{10, 0}, {20, 0}, {20, 10}, {30, 10}, {30, 20}, {20, 20}, {20, 30},
                    {10, 30}, {10, 20}, {0, 20}, {0, 10}, {10, 10}};
    agrees_with_cgal(plus);
    agrees_with_cgal(kShapes[0]);
    // Clockwise, repeated points or parallel neighbours: declined, never wrong.
    std::vector<SkeletonFace> faces;
    EXPECT_FALSE(wavefront_skeleton_faces(Ring(kShapes[0].rbegin(), kShapes[0].rend()), &faces));
    EXPECT_FALSE(wavefront_skeleton_faces({{0, 0}, {10, 0}, {10, 0}, {10, 5}, {5, 5}, {5, 10}, {0, 10}}, &faces));
    EXPECT_FALSE(wavefront_skeleton_faces({{0, 0}, {5, 0}, {10, 0}, {10, 5}, {5, 5}, {5, 10}, {0, 10}}, &faces));
    EXPECT_TRUE(faces.empty());
}

// The header promises empty faces on false; a footprint declined while its faces were being
// ordered (after the first faces were listed) used to leave those first faces behind.
TEST(WavefrontSkeleton, DeclinedLateLeavesNoFaces) {
    const Ring star{{11, 7}, {12, 7}, {13, 6}, {11, 9}, {11, 10}, {13, 11}, {11, 11}, {11, 14}, {8, 13}, {9, 11}, {7, 12}};
    std::vector<SkeletonFace> faces;
    EXPECT_FALSE(wavefront_skeleton_faces(star, &faces));
    EXPECT_TRUE(faces.empty()) << faces.size() << " faces left";
    agrees_with_cgal(star);
}

TEST(WavefrontSkeleton, SameFacesEveryRun) {
    const Ring ring = jittered(kShapes[4], 0.3, 7);
    std::vector<SkeletonFace> a, b;
    ASSERT_TRUE(wavefront_skeleton_faces(ring, &a));
    ASSERT_TRUE(wavefront_skeleton_faces(ring, &b));
    ASSERT_EQ(a.size(), b.size());
    for (size_t i = 0; i < a.size(); ++i) {
        EXPECT_EQ(a[i].points.size(), b[i].points.size());
        for (size_t j = 0; j < a[i].points.size(); ++j) {
            EXPECT_EQ(a[i].points[j].x, b[i].points[j].x);
            EXPECT_EQ(a[i].points[j].y, b[i].points[j].y);
            EXPECT_EQ(a[i].times[j], b[i].times[j]);
        }
    }
}

}  // namespace
}  // namespace citygen
