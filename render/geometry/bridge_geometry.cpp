#include "render/geometry/bridge_geometry.h"

#include <algorithm>
#include <cmath>

#include "common/ground.h"
#include "render/geometry/triangulate_polygon.h"
#include "render/materials/materials.h"

namespace citygen {

namespace {

// A pier's size: 1 m along the deck, across it the road's width less 1 m each side.
constexpr double kPierLength = 1;
constexpr double kPierInset = 1;
// A pier's foot reaches this far below the lowest ground at its corners, so no gap opens where
// the ground between them dips.
constexpr double kPierFooting = 1;

// The vertical face under the edge a->b of a counter-clockwise outline, from z_bottom(p) up to
// z_top(p), facing out: a trapezoid, planar as both heights are linear along the edge.
template <class Bottom, class Top>
PlanarFace side_face(Vec2 a, Vec2 b, Bottom z_bottom, Top z_top) {
    return {{{a.x, a.y, z_bottom(a)}, {b.x, b.y, z_bottom(b)}, {b.x, b.y, z_top(b)}, {a.x, a.y, z_top(a)}}, kCurb};
}

}  // namespace

std::vector<DeckLine> drawn_decks(const Scene& scene) {
    if (scene.terrain.empty()) return {};
    return bridge_decks(scene);
}

std::vector<DeckLine> drawn_path_decks(const Scene& scene) {
    if (scene.terrain.empty()) return {};
    return path_bridge_decks(scene);
}

std::vector<PlanarFace> deck_piece_faces(const DeckSurface& deck, const Ring& ring, double lift, uint16_t top_material) {
    std::vector<PlanarFace> faces;
    if (ring.size() < 3) return faces;
    Ring outline = ring;
    if (signed_area(outline) < 0) std::reverse(outline.begin(), outline.end());
    const auto top = [&](Vec2 p) { return deck.height(p) + lift; };
    const auto bottom = [&](Vec2 p) { return deck.height(p) - kDeckThickness; };
    const PolygonTriangulation tri = triangulate_polygon(outline);
    for (const auto& t : tri.triangles) {
        const Vec2 a = tri.points[t[0]], b = tri.points[t[1]], c = tri.points[t[2]];
        faces.push_back({{{a.x, a.y, top(a)}, {b.x, b.y, top(b)}, {c.x, c.y, top(c)}}, top_material});
        faces.push_back({{{a.x, a.y, bottom(a)}, {c.x, c.y, bottom(c)}, {b.x, b.y, bottom(b)}}, kCurb});
    }
    for (size_t k = 0, n = outline.size(); k < n; ++k) {
        const Vec2 a = outline[k], b = outline[(k + 1) % n];
        if (a != b) faces.push_back(side_face(a, b, bottom, top));
    }
    return faces;
}

std::vector<PlanarFace> deck_piers(const Scene& scene, const DeckLine& deck, double width) {
    std::vector<PlanarFace> faces;
    const Vec2 chord = deck.b - deck.a;
    const double span = length(chord);
    const double half_width = 0.5 * width - kPierInset;
    if (!(span > kPierSpacing) || !(half_width > 0)) return faces;
    const Vec2 u = chord * (1 / span), v = perp_left(u);
    const int bays = static_cast<int>(std::ceil(span / kPierSpacing));
    const auto underside = [&](Vec2 p) { return deck_height(deck, p) - kDeckThickness; };
    for (int k = 1; k < bays; ++k) {
        const Vec2 c = deck.a + chord * (static_cast<double>(k) / bays);
        const Vec2 along = u * (0.5 * kPierLength), across = v * half_width;
        const Vec2 corners[4] = {c - along - across, c + along - across, c + along + across, c - along + across};
        double ground = ground_height(scene, c.x, c.y);
        for (Vec2 p : corners) ground = std::min(ground, ground_height(scene, p.x, p.y));
        if (underside(c) - ground < kPierClearance) continue;
        const auto foot = [&](Vec2) { return ground - kPierFooting; };
        for (int e = 0; e < 4; ++e) faces.push_back(side_face(corners[e], corners[(e + 1) % 4], foot, underside));
    }
    return faces;
}

}  // namespace citygen
