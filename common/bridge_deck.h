// Bridges on a height field, one rule for both programs: a road, path or rail tagged `bridge`
// keeps its own deck instead of following the ground under it. A bridge is a chain of edges (one
// per segment of its way) between the nodes where it meets edges of its network (roads, or
// paths and rails) on the ground; its deck is level
// across and straight along the chain, from the drawn ground at one end to the other, so it
// meets the roads at both ends and spans whatever lies between them (a valley, a river, a road
// below). Where bridges meet on a deck (a junction on a viaduct) the deck's height there is the
// length-weighted mean of the chains' far ends, so every chain stays straight. osmparse carves
// the field under the decks (fit_terrain.h); render draws them, their slabs and piers
// (render/geometry/bridge_geometry.h); the GeoJSON gives their heights.
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include "common/geometry.h"
#include "common/scene.h"

namespace citygen {

// The slab under a deck's surface: its side faces are what makes a bridge read as one from the
// side, and the field under the deck is kept at least this much below it.
constexpr double kDeckThickness = 0.8;
// Piers stand every kPierSpacing metres along a deck where its underside is at least
// kPierClearance above the ground; lower decks rest on their abutments.
constexpr double kPierSpacing = 25;
constexpr double kPierClearance = 2;

// One road edge's deck: the chord of its centreline (a at its first point, b at its last) and
// the deck's heights there; where a and b lie along the whole bridge (metres from its start),
// its length and which of its ends stand on the ground (not on another deck).
struct DeckLine {
    bool valid = false;  // false for a road that is not a bridge
    uint32_t bridge = 0;  // which bridge (chain) of the scene's the edge belongs to, from 0
    Vec2 a, b;
    double za = 0, zb = 0;
    double along_a = 0, along_b = 0, bridge_length = 0;
    bool starts_on_ground = false, ends_on_ground = false;
};

// The decks of every road (invalid where the road is not a bridge) on the field, or at flat_z
// without one; of every path and rail the same, their chains ending where they meet paths on the
// ground (the two networks meet only on the ground).
std::vector<DeckLine> bridge_decks(const HeightField& field, double flat_z, const std::vector<RoadEdge>& roads);
std::vector<DeckLine> bridge_decks(const HeightField& field, double flat_z, const std::vector<PathEdge>& paths);
std::vector<DeckLine> bridge_decks(const Scene& scene);
std::vector<DeckLine> path_bridge_decks(const Scene& scene);

// The surface a piece on a deck lies on: its bridge edge's deck, or at a junction on a viaduct (a
// joint all of whose edges are bridges) the deck of the edge whose quad is nearest each point
// (then whose chord), so the joint meets every edge's end as a joint on the ground does. No
// edges (invalid) for a piece on the ground.
struct DeckSurface {
    const std::vector<DeckLine>* decks = nullptr;
    std::vector<uint32_t> edges;     // into decks
    std::vector<const Ring*> quads;  // the edges' quads, at a joint
    bool valid() const { return !edges.empty(); }
    double height(Vec2 p) const;
};
// The deck of a road, or of a path (decks from path_bridge_decks).
DeckSurface edge_deck(const std::vector<DeckLine>& decks, uint32_t edge);
DeckSurface joint_deck(const Scene& scene, const std::vector<DeckLine>& decks, const Joint& joint);
DeckSurface path_joint_deck(const Scene& scene, const std::vector<DeckLine>& path_decks, const Joint& joint);
// A sidewalk strip lies on its road's deck, a corner on its joint's.
DeckSurface sidewalk_deck(const Scene& scene, const std::vector<DeckLine>& decks, const Sidewalk& sidewalk);

// Where p lies along the deck: its projection onto the chord, 0 at a and 1 at b (not clamped).
double deck_parameter(const DeckLine& deck, Vec2 p);

// The deck's surface height at p: linear along the chord, level across it, clamped at the ends.
double deck_height(const DeckLine& deck, Vec2 p);

// Where p (projected on the chord, not clamped) lies along the whole bridge, metres from its start.
double deck_along(const DeckLine& deck, Vec2 p);

// What stands at a point (a street lamp) stands on the top surface there: a bridge's deck where
// the point lies on it (within 2.5 m of a road's carriageway: its sidewalk or parapet; within
// 1 m of a footbridge's or rail bridge's strip: its railing), the ground elsewhere. Built once
// per scene; without a field, or without bridges, it is the ground.
class StandingSurface {
public:
    explicit StandingSurface(const Scene& scene);
    double height(Vec2 p) const;

private:
    const Scene& scene_;
    std::vector<DeckLine> decks_;
    std::vector<double> reach_;  // per deck: how far from its chord a point is on it
    std::unordered_map<int64_t, std::vector<uint32_t>> cells_;  // decks by kCell-metre cell
    std::vector<uint32_t> long_decks_;  // decks over more than kMaxCells cells, tried for every point
    static constexpr int64_t kMaxCells = 4096;
    static constexpr double kCell = 64;
    static int64_t cell_key(int64_t i, int64_t j) { return i * 4194304 + j; }
};

}  // namespace citygen
