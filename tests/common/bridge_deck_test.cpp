// Bridge decks (common/bridge_deck.h): chains of bridge edges, straight between their ends on
// the ground, whatever the edges' order and direction; junctions on a deck.
#include <gtest/gtest.h>

#include "common/bridge_deck.h"

using namespace citygen;

namespace {

RoadEdge edge(int64_t from, int64_t to, Vec2 a, Vec2 b, bool bridge) {
    RoadEdge r;
    r.from_node = from;
    r.to_node = to;
    r.centreline = {a, b};
    r.width = 6;
    r.bridge = bridge;
    return r;
}

// A field over [-100, 100]^2, 1 m cells, a valley along y: z = 0.5 |x| (0 at its floor).
HeightField valley() {
    HeightField f;
    f.origin = {-100, -100};
    f.cell = 1;
    f.nx = f.ny = 201;
    for (uint32_t j = 0; j < f.ny; ++j)
        for (uint32_t i = 0; i < f.nx; ++i) f.heights.push_back(static_cast<float>(0.5 * std::fabs(-100.0 + i)));
    return f;
}

}  // namespace

TEST(BridgeDecks, AChainIsStraightBetweenItsEndsOnTheGroundWhateverItsEdgesOrderAndDirection) {
    // Roads on the ground to nodes 1 and 5; the bridge 1-2-3-4-5 over the valley, its edges
    // listed out of order and two of them drawn backwards.
    const std::vector<RoadEdge> roads = {
        edge(10, 1, {-80, 0}, {-40, 0}, false),
        edge(3, 2, {0, 0}, {-20, 0}, true),
        edge(4, 5, {20, 0}, {40, 0}, true),
        edge(1, 2, {-40, 0}, {-20, 0}, true),
        edge(4, 3, {20, 0}, {0, 0}, true),
        edge(5, 11, {40, 0}, {80, 0}, false),
    };
    const std::vector<DeckLine> decks = bridge_decks(valley(), 0, roads);
    EXPECT_FALSE(decks[0].valid);
    EXPECT_FALSE(decks[5].valid);
    for (int e : {1, 2, 3, 4}) {
        ASSERT_TRUE(decks[e].valid) << e;
        // The ground is 20 m at both ends: a level deck, 20 m above the valley's floor.
        EXPECT_NEAR(deck_height(decks[e], roads[e].centreline.front()), 20, 1e-6) << e;
        EXPECT_NEAR(deck_height(decks[e], roads[e].centreline.back()), 20, 1e-6) << e;
        EXPECT_EQ(decks[e].bridge_length, 80);
        EXPECT_TRUE(decks[e].starts_on_ground && decks[e].ends_on_ground);
    }
    // The chain runs from node 5 (x = 40) to node 1 (x = -40).
    EXPECT_NEAR(deck_along(decks[1], {0, 0}), 40, 1e-9);
    EXPECT_NEAR(deck_along(decks[3], {-35, 3}), 75, 1e-9);
}

TEST(BridgeDecks, ARisingChainRisesLinearlyAlongItsLength) {
    HeightField f = valley();
    for (uint32_t j = 0; j < f.ny; ++j)  // a slope up to the east instead: z = 0.1 (x + 100)
        for (uint32_t i = 0; i < f.nx; ++i) f.heights[j * f.nx + i] = static_cast<float>(0.1 * i);
    const std::vector<RoadEdge> roads = {
        edge(10, 1, {-90, 0}, {-60, 0}, false), edge(1, 2, {-60, 0}, {-50, 0}, true),
        edge(2, 3, {-50, 0}, {20, 0}, true),    edge(3, 11, {20, 0}, {60, 0}, false),
    };
    const std::vector<DeckLine> decks = bridge_decks(f, 0, roads);
    EXPECT_NEAR(decks[1].za, 4, 1e-4);
    EXPECT_NEAR(decks[1].zb, 5, 1e-4);
    EXPECT_NEAR(decks[2].za, 5, 1e-4);
    EXPECT_NEAR(decks[2].zb, 12, 1e-4);
    EXPECT_NEAR(deck_height(decks[2], {-15, 2}), 8.5, 1e-4) << "level across, linear along";
    EXPECT_NEAR(deck_height(decks[2], {90, 0}), 12, 1e-4) << "clamped beyond the end";
}

TEST(BridgeDecks, WhereChainsMeetOnADeckEachStaysStraight) {
    // Three bridges from the ground meet at node 1 on the deck: its height is the mean of their
    // ground ends weighted by 1 / length.
    HeightField f = valley();
    const std::vector<RoadEdge> roads = {
        edge(1, 2, {0, 0}, {-40, 0}, true),   // ground 20 m away 40 m
        edge(1, 3, {0, 0}, {80, 0}, true),    // 40 m away 80 m
        edge(4, 1, {0, -60}, {0, 0}, true),   // 0 m (the valley floor) away 60 m
        edge(2, 20, {-40, 0}, {-60, 0}, false), edge(3, 30, {80, 0}, {90, 0}, false),
        edge(40, 4, {0, -90}, {0, -60}, false),
    };
    const std::vector<DeckLine> decks = bridge_decks(f, 0, roads);
    const double expected = (20 / 40.0 + 40 / 80.0 + 0 / 60.0) / (1 / 40.0 + 1 / 80.0 + 1 / 60.0);
    EXPECT_NEAR(decks[0].za, expected, 1e-6);
    EXPECT_NEAR(decks[1].za, expected, 1e-6);
    EXPECT_NEAR(decks[2].zb, expected, 1e-6);
    EXPECT_NEAR(decks[0].zb, 20, 1e-6);
    EXPECT_FALSE(decks[0].starts_on_ground);
    EXPECT_TRUE(decks[0].ends_on_ground);
    EXPECT_NEAR(deck_along(decks[0], {-10, 0}), 10, 1e-9) << "from the junction on the deck";
}

TEST(BridgeDecks, WithoutAFieldADeckLiesOnTheFlatGround) {
    const std::vector<RoadEdge> roads = {edge(1, 2, {0, 0}, {30, 0}, true)};
    const std::vector<DeckLine> decks = bridge_decks(HeightField{}, 0.5, roads);
    ASSERT_TRUE(decks[0].valid);
    EXPECT_EQ(decks[0].za, 0.5);
    EXPECT_EQ(decks[0].zb, 0.5);
}

TEST(DeckSurface, AJointsVertexAtAQuadsCornerLiesOnThatQuadsDeck) {
    // Two bridges leave a junction on a viaduct at (0, 0): A to the west, rising, and B to the
    // south, falling. A's quad ends skewed: its corner (-1, -3) lies inside B's quad, nearer B's
    // chord than A's.
    DeckLine a, b;
    a.valid = b.valid = true;
    a.a = b.a = {0, 0};
    a.b = {-40, 0};
    b.b = {0, -40};
    a.za = b.za = 10;
    a.zb = 20;
    b.zb = 0;
    const std::vector<DeckLine> decks = {a, b};
    const Ring quad_a = {{-1, -3}, {-3, 3}, {-40, 3}, {-40, -3}};
    const Ring quad_b = {{-3, -1}, {-3, -40}, {3, -40}, {3, -1}};
    DeckSurface joint;
    joint.decks = &decks;
    joint.edges = {0, 1};
    joint.quads = {&quad_a, &quad_b};
    EXPECT_NEAR(joint.height({-1, -3}), deck_height(a, {-1, -3}), 1e-9) << "A's corner: A's deck, no step";
    EXPECT_NEAR(deck_height(a, {-1, -3}), 10.25, 1e-9);
    EXPECT_NEAR(joint.height({1, -3}), deck_height(b, {1, -3}), 1e-9) << "inside B only: B's deck";
}
