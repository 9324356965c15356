#include "osmparse/terrain/fit_terrain.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "common/bridge_deck.h"
#include "common/ground.h"
#include "common/grid_nodes.h"
#include "common/stairs.h"

namespace citygen {

namespace {

GridLayout layout_of(const HeightField& f) { return {f.origin, f.cell, f.nx, f.ny}; }

// One pass of a box filter of 2r + 1 nodes along rows (step 1) or columns (step nx), the edge
// nodes repeated beyond the grid. Lines are independent, so they are filtered side by side.
void box_pass(std::vector<float>& h, uint32_t nx, uint32_t ny, int r, bool along_rows) {
    const uint32_t lines = along_rows ? ny : nx, n = along_rows ? nx : ny;
    const size_t step = along_rows ? 1 : nx;
    tbb::parallel_for(tbb::blocked_range<uint32_t>(0, lines, 64), [&](const tbb::blocked_range<uint32_t>& range) {
        std::vector<double> line(n);
        for (uint32_t l = range.begin(); l < range.end(); ++l) {
            const size_t first = along_rows ? static_cast<size_t>(l) * nx : l;
            for (uint32_t k = 0; k < n; ++k) line[k] = h[first + k * step];
            const auto at = [&](long k) { return line[static_cast<size_t>(std::clamp<long>(k, 0, n - 1))]; };
            double sum = 0;
            for (long k = -r; k <= r; ++k) sum += at(k);
            for (uint32_t k = 0; k < n; ++k) {
                h[first + k * step] = static_cast<float>(sum / (2 * r + 1));
                sum += at(static_cast<long>(k) + r + 1) - at(static_cast<long>(k) - r);
            }
        }
    });
}

// The field smoothed at kProfileSmoothing: three box passes each way approach a Gaussian; three
// boxes of 2r + 1 nodes have a variance of r (r + 1) cells squared.
HeightField smoothed(const HeightField& field) {
    HeightField s = field;
    const double sigma_cells = kProfileSmoothing / field.cell;
    const int r = static_cast<int>(std::floor((-1 + std::sqrt(1 + 4 * sigma_cells * sigma_cells)) / 2 + 0.5));
    if (r < 1) return s;
    for (int pass = 0; pass < 3; ++pass) {
        box_pass(s.heights, s.nx, s.ny, r, true);
        box_pass(s.heights, s.nx, s.ny, r, false);
    }
    return s;
}

// What a node is fitted to: the way that claims it most (weight 1 in a corridor, falling to 0
// across the shoulder); among equals a road before a path (a footway beside a road is level
// with the road, not the road tilted towards the footway's axis), then the nearer, then the
// earlier.
struct NodeFit {
    float weight = 0;
    uint8_t rank = 255;
    float distance = std::numeric_limits<float>::infinity();
    float level = 0;
};

struct Corridor {
    const std::vector<Vec2>* centreline;
    double half_width;  // of the surface that must be level: carriageway and sidewalks
    uint8_t rank;       // 0 roads, 1 paths
};

// The half width of the surface that must be level across a road: carriageway and sidewalks.
double corridor_half_width(const RoadEdge& r, const FitWidths& widths) {
    const bool sidewalk = r.sidewalk_left || r.sidewalk_right;
    return r.width / 2 + (sidewalk ? widths.sidewalk : 0);
}

void fit_to_corridor(const Corridor& c, const HeightField& profile, double margin, double shoulder,
                     std::vector<NodeFit>& fits) {
    const GridLayout g = layout_of(profile);
    const double level_reach = c.half_width + margin;
    const std::vector<Vec2>& line = *c.centreline;
    for (size_t k = 0; k + 1 < line.size(); ++k) {
        const Vec2 a = line[k], b = line[k + 1];
        for_each_node_near(g, a, b, level_reach + shoulder, [&](uint32_t i, uint32_t j, double d, double t) {
            const auto weight = static_cast<float>(shoulder_weight(d - level_reach, shoulder));
            NodeFit& f = fits[g.index(i, j)];
            if (weight < f.weight) return;
            if (weight == f.weight && (c.rank > f.rank || (c.rank == f.rank && !(d < f.distance)))) return;
            const Vec2 p = a + (b - a) * t;
            f = {weight, c.rank, static_cast<float>(d), static_cast<float>(profile.at(p.x, p.y))};
        });
    }
}

// The field under the bridges (common/bridge_deck.h, on the fitted field). At each end on the
// ground, up to a cell past where the bridge's surface begins (its quads start at the edge of the
// joint there), the field is the deck itself, an abutment: the joint and the way's end lie on it
// and meet the deck without a step. Beyond, the field is kept kDeckThickness + kUnderDeckGap below
// the deck, so no hill or bank pokes through it; the clearance grows along a 1:2 slope from the
// abutment. Counts the nodes set or lowered.
struct UnderDecks {
    int64_t abutment = 0, carved = 0;
};

// One bridge edge's deck, how far from its chord the field is fitted to it, and where along its
// bridge the abutments end (metres).
struct DeckReach {
    DeckLine deck;
    double reach;
    double start, end;
};

// The decks of one network's bridge edges (roads, or paths and rails); `half_width(e)`: the half
// width of edge e's surface.
template <class Edge, class HalfWidth>
void add_deck_reaches(const HeightField& field, const std::vector<Edge>& edges, HalfWidth half_width,
                      double margin, std::vector<DeckReach>& out) {
    const std::vector<DeckLine> decks = bridge_decks(field, 0, edges);
    // Per bridge, where its surface begins and ends (metres along it): its quads' extent.
    std::vector<std::pair<double, double>> surface;
    for (size_t e = 0; e < edges.size(); ++e) {
        const DeckLine& deck = decks[e];
        if (!deck.valid) continue;
        if (surface.size() <= deck.bridge) surface.resize(deck.bridge + 1, {1e300, -1e300});
        for (Vec2 c : edges[e].quad) {
            const double along = deck_along(deck, c);
            surface[deck.bridge].first = std::min(surface[deck.bridge].first, along);
            surface[deck.bridge].second = std::max(surface[deck.bridge].second, along);
        }
    }
    for (size_t e = 0; e < edges.size(); ++e) {
        const DeckLine& deck = decks[e];
        if (!deck.valid) continue;
        const auto [first, last] = surface[deck.bridge];
        const double start = (first <= last ? std::max(0.0, first) : 0.0) + margin;
        const double end = (first <= last ? std::min(deck.bridge_length, last) : deck.bridge_length) - margin;
        out.push_back({deck, half_width(edges[e]) + margin, start, end});
    }
}

UnderDecks fit_under_decks(HeightField& field, const std::vector<DeckReach>& decks) {
    const GridLayout g = layout_of(field);
    // Two passes: the carving under every deck, then the abutments, which win where a bridge's
    // end lies within another's reach (a ramp beside a lower bridge): a step where a bridge
    // meets its road shows more than the other deck's slab meeting a bank.
    UnderDecks count;
    for (const bool abutments : {false, true})
        for (const DeckReach& d : decks) {
            const DeckLine& deck = d.deck;
            for_each_node_near(g, deck.a, deck.b, d.reach, [&](uint32_t i, uint32_t j, double, double) {
                const Vec2 p = g.node(i, j);
                const double along = std::clamp(deck_along(deck, p), 0.0, deck.bridge_length);
                double from_abutment = std::numeric_limits<double>::infinity();
                if (deck.starts_on_ground) from_abutment = along - d.start;
                if (deck.ends_on_ground) from_abutment = std::min(from_abutment, d.end - along);
                float& h = field.heights[g.index(i, j)];
                if (abutments && from_abutment <= 0) {
                    // The deck's line continued past its end, not clamped: the field's
                    // triangles then reproduce it exactly, and the ground at the bridge's end
                    // (which sets the deck's height there) stays what it was.
                    const double t = deck_parameter(deck, p);
                    h = static_cast<float>(deck.za + (deck.zb - deck.za) * t), ++count.abutment;
                } else if (!abutments && from_abutment > 0) {
                    const double clearance = std::min(kDeckThickness + kUnderDeckGap, 0.5 * from_abutment);
                    const auto allowed = static_cast<float>(deck_height(deck, p) - clearance);
                    if (h > allowed) h = allowed, ++count.carved;
                }
            });
        }
    return count;
}

// Steps the field leaves on the DEM (they are not fitted) are drawn as a stair where steep
// (common/stairs.h): its treads rise along the line between its ends, so where the DEM bulges
// above that line it would bury them. Nodes above the line within the steps' half width and a
// cell's diagonal are lowered to it (a cut), blending back over the shoulder; nodes a way's
// corridor levelled, and those beyond the stair's ends (the ways there), are left. The plans are
// made first, so one stair's cut does not move another's ends.
int64_t cut_under_stairs(HeightField& field, const std::vector<PathEdge>& paths, const std::vector<NodeFit>& fits,
                         double margin, double shoulder) {
    const GridLayout g = layout_of(field);
    std::vector<std::pair<StairPlan, double>> stairs;
    for (const PathEdge& p : paths)
        if (StairPlan plan; stair_between_ends(field, p, &plan)) stairs.push_back({plan, p.width / 2 + margin});
    int64_t cut = 0;
    for (const auto& stair : stairs) {
        const StairPlan& plan = stair.first;  // named, not bound: a lambda cannot capture a structured binding in C++17
        const double reach = stair.second;
        for_each_node_near(g, plan.low, plan.high, reach + shoulder, [&](uint32_t i, uint32_t j, double d, double t) {
            const size_t n = g.index(i, j);
            if (!(t > 0 && t < 1) || fits[n].weight >= 1) return;
            const double line = plan.z_low + t * (plan.z_high - plan.z_low);
            const double w = shoulder_weight(d - reach, shoulder);
            float& h = field.heights[n];
            const auto lowered = static_cast<float>(w * line + (1 - w) * h);
            if (lowered < h) h = lowered, ++cut;
        });
    }
    return cut;
}

}  // namespace

void fit_terrain_to_ways(HeightField& field, const std::vector<RoadEdge>& roads,
                         const std::vector<PathEdge>& paths, const FitWidths& widths, ParseReport& report) {
    if (field.empty()) return;
    const HeightField profile = smoothed(field);
    // Every cell a way's surface touches has all four nodes within its corridor: the drawn
    // surface is level across the way, not tilted by a node beyond it.
    const double margin = field.cell * std::sqrt(2.0);
    const double shoulder = shoulder_width(field);
    std::vector<NodeFit> fits(field.heights.size());
    int64_t bridges = 0, path_bridges = 0;
    for (const RoadEdge& r : roads) {
        if (r.bridge) {
            ++bridges;
            continue;
        }
        fit_to_corridor({&r.centreline, corridor_half_width(r, widths), 0}, profile, margin, shoulder, fits);
    }
    for (const PathEdge& p : paths) {
        if (p.bridge) {
            ++path_bridges;
            continue;
        }
        if (p.path_class == PathClass::Steps) continue;  // on the DEM (note_steps)
        fit_to_corridor({&p.centreline, p.width / 2, 1}, profile, margin, shoulder, fits);
    }
    int64_t level = 0, blended = 0;
    for (size_t n = 0; n < fits.size(); ++n) {
        const NodeFit& f = fits[n];
        if (f.weight <= 0) continue;
        field.heights[n] = f.weight * f.level + (1 - f.weight) * field.heights[n];
        ++(f.weight == 1 ? level : blended);
    }
    std::vector<DeckReach> reaches;
    add_deck_reaches(field, roads, [&](const RoadEdge& r) {
        return r.width / 2 + (r.sidewalk_left || r.sidewalk_right ? widths.sidewalk : 0);
    }, margin, reaches);
    add_deck_reaches(field, paths, [](const PathEdge& p) { return p.width / 2; }, margin, reaches);
    const UnderDecks decks = fit_under_decks(field, reaches);
    const int64_t cut = cut_under_stairs(field, paths, fits, margin, shoulder);
    if (level > 0) report.note(ReportKind::TerrainNodes, ReportReason::TerrainUnderWay, level);
    if (blended > 0) report.note(ReportKind::TerrainNodes, ReportReason::TerrainWayShoulder, blended);
    if (decks.abutment > 0) report.note(ReportKind::TerrainNodes, ReportReason::TerrainUnderAbutment, decks.abutment);
    if (decks.carved > 0) report.note(ReportKind::TerrainNodes, ReportReason::TerrainUnderDeck, decks.carved);
    if (cut > 0) report.note(ReportKind::TerrainNodes, ReportReason::TerrainUnderStair, cut);
    if (bridges > 0) report.note(ReportKind::RoadEdges, ReportReason::BridgeOnItsDeck, bridges);
    if (path_bridges > 0) report.note(ReportKind::PathEdges, ReportReason::BridgeOnItsDeck, path_bridges);
}

void note_steps(const Scene& scene, ParseReport& report) {
    if (scene.terrain.empty()) return;
    int64_t stairs = 0, draped = 0;
    for (const PathEdge& p : scene.paths) {
        if (p.path_class != PathClass::Steps || p.bridge) continue;  // steps on a deck: counted as bridges
        StairPlan plan;
        ++(plan_stair(scene, p, &plan) ? stairs : draped);
    }
    if (draped > 0) report.note(ReportKind::PathEdges, ReportReason::StepsOnTheGround, draped);
    if (stairs > 0) report.note(ReportKind::PathEdges, ReportReason::StepsAsStair, stairs);
}

std::vector<uint8_t> way_corridor_nodes(const HeightField& field, const std::vector<RoadEdge>& roads,
                                        const std::vector<PathEdge>& paths, const FitWidths& widths) {
    std::vector<uint8_t> under(field.heights.size(), 0);
    if (field.empty()) return under;
    const GridLayout g = layout_of(field);
    const double margin = field.cell * std::sqrt(2.0);  // as fit_terrain_to_ways's corridors
    const auto mark = [&](const std::vector<Vec2>& line, double reach) {
        for (size_t k = 0; k + 1 < line.size(); ++k)
            for_each_node_near(g, line[k], line[k + 1], reach,
                               [&](uint32_t i, uint32_t j, double, double) { under[g.index(i, j)] = 1; });
    };
    for (const RoadEdge& r : roads) mark(r.centreline, corridor_half_width(r, widths) + margin);
    for (const PathEdge& p : paths) mark(p.centreline, p.width / 2 + margin);
    return under;
}

void level_still_water(HeightField& field, const std::vector<LandCover>& land_cover, ParseReport& report) {
    if (field.empty()) return;
    const GridLayout g = layout_of(field);
    const double margin = field.cell * std::sqrt(2.0);
    int64_t levelled = 0, falling = 0, nodes = 0;
    for (const LandCover& c : land_cover) {
        if (c.cover != LandCoverClass::Water) continue;
        std::vector<const Ring*> rings{&c.outer};
        for (const Ring& hole : c.holes) rings.push_back(&hole);
        // The shore's heights on the drawn surface, sampled at least once a cell.
        double lowest = std::numeric_limits<double>::infinity(), highest = -lowest;
        for (const Ring* ring : rings)
            for (size_t a = 0; a < ring->size(); ++a) {
                const Vec2 p = (*ring)[a], q = (*ring)[(a + 1) % ring->size()];
                const int steps = 1 + static_cast<int>(length(q - p) / field.cell);
                for (int s = 0; s < steps; ++s) {
                    const Vec2 x = p + (q - p) * (static_cast<double>(s) / steps);
                    const double h = field_surface_height(field, x.x, x.y);
                    lowest = std::min(lowest, h), highest = std::max(highest, h);
                }
            }
        if (!(lowest <= highest)) continue;
        if (highest - lowest > kMaxStillWaterFall) {
            ++falling;
            continue;
        }
        ++levelled;
        const auto level = static_cast<float>(lowest);
        const auto set = [&](uint32_t i, uint32_t j) {
            float& h = field.heights[g.index(i, j)];
            nodes += h != level;
            h = level;
        };
        for_each_node_inside(g, rings, set);
        for (const Ring* ring : rings)
            for (size_t a = 0; a < ring->size(); ++a)
                for_each_node_near(g, (*ring)[a], (*ring)[(a + 1) % ring->size()], margin,
                                   [&](uint32_t i, uint32_t j, double, double) { set(i, j); });
    }
    if (levelled > 0) report.note(ReportKind::LandCoverWater, ReportReason::WaterLevelled, levelled);
    if (falling > 0) report.note(ReportKind::LandCoverWater, ReportReason::WaterOnASlope, falling);
    if (nodes > 0) report.note(ReportKind::TerrainNodes, ReportReason::TerrainUnderWater, nodes);
}

void raise_piers(HeightField& field, const std::vector<LandCover>& land_cover, ParseReport& report) {
    const std::vector<uint8_t> pier = pier_nodes(field, land_cover);
    int64_t raised = 0;
    for (size_t n = 0; n < pier.size(); ++n)
        if (pier[n]) field.heights[n] = static_cast<float>(kPierDeck), ++raised;
    if (raised > 0) report.note(ReportKind::TerrainNodes, ReportReason::TerrainUnderPier, raised);
}

}  // namespace citygen
