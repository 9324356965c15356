// Bridges on a height field (common/bridge_deck.h): a bridge road's surface on its deck instead
// of draped on the ground, the slab under it (underside and side faces) and its piers, and the
// sidewalks along it on the same deck. Both geometry modes build the same faces (stored as
// triangles, procedural as planar faces). Without a field a bridge is drawn as any road.
#pragma once

#include <cstdint>
#include <vector>

#include "common/bridge_deck.h"
#include "common/scene.h"
#include "render/geometry/planar_face.h"

namespace citygen {

// The decks render draws, one per road (common/bridge_deck.h), or per path: none without a height
// field, where bridges lie on the flat ground as every road does.
std::vector<DeckLine> drawn_decks(const Scene& scene);
std::vector<DeckLine> drawn_path_decks(const Scene& scene);

// A polygon on a deck, `lift` above its surface, with its slab (kDeckThickness under the
// surface: an underside facing down and a side face on every edge facing out) and, for a road,
// its piers (across the way's `width` less 1 m each side): the way's own surface, or a sidewalk
// along it (lift: its curb top).
std::vector<PlanarFace> deck_piece_faces(const DeckSurface& deck, const Ring& ring, double lift, uint16_t top_material);
std::vector<PlanarFace> deck_piers(const Scene& scene, const DeckLine& deck, double width);

}  // namespace citygen
