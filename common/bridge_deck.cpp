#include "common/bridge_deck.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tuple>
#include <unordered_map>

#include "common/ground.h"

namespace citygen {

namespace {

template <class Edge>
double centreline_length(const Edge& r) {
    double total = 0;
    for (size_t k = 0; k + 1 < r.centreline.size(); ++k) total += length(r.centreline[k + 1] - r.centreline[k]);
    return total;
}

// A bridge as a chain of edges between two terminal nodes (where it meets a road on the ground,
// another deck's chain, or ends), each edge with its direction along the chain.
struct Chain {
    std::vector<uint32_t> edges;
    std::vector<bool> forward;  // the edge runs from_node -> to_node along the chain
    int64_t first = 0, last = 0;
    double length = 0;
};

// The edges (roads, or paths and rails) and the nodes where they meet.
template <class Edge>
class BridgeGraph {
public:
    explicit BridgeGraph(const std::vector<Edge>& roads) : roads_(roads) {
        for (uint32_t e = 0; e < roads.size(); ++e) {
            edges_at_[roads[e].from_node].push_back(e);
            if (roads[e].to_node != roads[e].from_node) edges_at_[roads[e].to_node].push_back(e);
        }
    }
    // Every edge there is a bridge: the node is on a deck.
    bool on_deck(int64_t node) const {
        for (uint32_t e : edges_at_.at(node))
            if (!roads_[e].bridge) return false;
        return true;
    }
    // A chain runs through a node on a deck with exactly two edges; it ends anywhere else.
    bool terminal(int64_t node) const { return !on_deck(node) || edges_at_.at(node).size() != 2; }
    int64_t other_node(uint32_t e, int64_t node) const {
        return roads_[e].from_node == node ? roads_[e].to_node : roads_[e].from_node;
    }
    uint32_t other_edge(int64_t node, uint32_t e) const {
        const std::vector<uint32_t>& at = edges_at_.at(node);
        return at[0] == e ? at[1] : at[0];
    }
    Vec2 position(int64_t node, uint32_t e) const {
        return roads_[e].from_node == node ? roads_[e].centreline.front() : roads_[e].centreline.back();
    }

    // The chain through bridge edge e, from one terminal to the other (a closed loop of deck
    // nodes ends where it started).
    Chain chain_through(uint32_t e) const {
        // Back to the terminal before e.
        int64_t node = roads_[e].from_node;
        uint32_t edge = e;
        while (!terminal(node)) {
            edge = other_edge(node, edge);
            node = other_node(edge, node);
            if (edge == e) break;  // a loop
        }
        Chain c;
        c.first = node;
        for (size_t guard = 0; guard <= roads_.size(); ++guard) {
            c.edges.push_back(edge);
            c.forward.push_back(roads_[edge].from_node == node);
            c.length += centreline_length(roads_[edge]);
            node = other_node(edge, node);
            if (terminal(node)) break;
            edge = other_edge(node, edge);
            if (edge == c.edges.front()) break;  // around the loop once
        }
        c.last = node;
        return c;
    }

private:
    const std::vector<Edge>& roads_;
    std::unordered_map<int64_t, std::vector<uint32_t>> edges_at_;
};

template <class Edge>
std::vector<DeckLine> decks_of(const HeightField& field, double flat_z, const std::vector<Edge>& roads) {
    std::vector<DeckLine> decks(roads.size());
    const auto ground = [&](Vec2 p) { return field.empty() ? flat_z : field_surface_height(field, p.x, p.y); };
    const BridgeGraph<Edge> graph(roads);
    std::vector<Chain> chains;
    std::vector<bool> chained(roads.size(), false);
    for (uint32_t e = 0; e < roads.size(); ++e) {
        if (!roads[e].bridge || chained[e] || roads[e].centreline.size() < 2) continue;
        chains.push_back(graph.chain_through(e));
        for (uint32_t c : chains.back().edges) chained[c] = true;
    }
    // Heights at the chains' ends: the ground where a chain meets a road on the ground; where
    // chains meet on a deck, the mean of their far ends weighted by 1 / length (what keeps each
    // chain straight), found by Gauss-Seidel sweeps from the ground's height.
    std::unordered_map<int64_t, double> end_z;
    std::vector<int64_t> deck_ends;  // in first-seen order, for a fixed sweep order
    for (const Chain& c : chains)
        for (const auto& [node, edge] : {std::pair{c.first, c.edges.front()}, std::pair{c.last, c.edges.back()}})
            if (end_z.emplace(node, ground(graph.position(node, edge))).second && graph.on_deck(node))
                deck_ends.push_back(node);
    if (!deck_ends.empty()) {
        std::unordered_map<int64_t, std::vector<const Chain*>> chains_at;
        for (const Chain& c : chains) {
            chains_at[c.first].push_back(&c);
            if (c.last != c.first) chains_at[c.last].push_back(&c);
        }
        for (int sweep = 0; sweep < 200; ++sweep)
            for (int64_t node : deck_ends) {
                double sum = 0, weight = 0;
                for (const Chain* c : chains_at[node]) {
                    const double w = 1 / std::max(c->length, 1.0);
                    sum += w * end_z[c->first == node ? c->last : c->first];
                    weight += w;
                }
                if (weight > 0) end_z[node] = sum / weight;
            }
    }
    for (const Chain& c : chains) {
        const double z0 = end_z[c.first], z1 = end_z[c.last];
        const double span = std::max(c.length, 1e-9);
        double along = 0;
        for (size_t k = 0; k < c.edges.size(); ++k) {
            const Edge& r = roads[c.edges[k]];
            const double l = centreline_length(r);
            DeckLine& d = decks[c.edges[k]];
            d.valid = true;
            d.bridge = static_cast<uint32_t>(&c - chains.data());
            d.a = r.centreline.front();
            d.b = r.centreline.back();
            d.bridge_length = c.length;
            d.starts_on_ground = !graph.on_deck(c.first);
            d.ends_on_ground = !graph.on_deck(c.last);
            // Along the chain the edge runs a -> b when it is forward, b -> a otherwise.
            d.along_a = c.forward[k] ? along : along + l;
            d.along_b = c.forward[k] ? along + l : along;
            d.za = z0 + (z1 - z0) * std::clamp(d.along_a / span, 0.0, 1.0);
            d.zb = z0 + (z1 - z0) * std::clamp(d.along_b / span, 0.0, 1.0);
            along += l;
        }
    }
    return decks;
}

template <class Edge>
DeckSurface joint_deck_of(const std::vector<Edge>& edges, const std::vector<DeckLine>& decks, const Joint& joint) {
    DeckSurface s;
    s.decks = &decks;
    for (uint32_t e : joint.edges)
        if (e >= decks.size() || e >= edges.size() || !decks[e].valid) return s;
    if (joint.polygon.empty()) return s;
    s.edges = joint.edges;
    for (uint32_t e : joint.edges) s.quads.push_back(&edges[e].quad);
    return s;
}

}  // namespace

std::vector<DeckLine> bridge_decks(const HeightField& field, double flat_z, const std::vector<RoadEdge>& roads) {
    return decks_of(field, flat_z, roads);
}

std::vector<DeckLine> bridge_decks(const HeightField& field, double flat_z, const std::vector<PathEdge>& paths) {
    return decks_of(field, flat_z, paths);
}

std::vector<DeckLine> bridge_decks(const Scene& scene) {
    return bridge_decks(scene.terrain, scene.ground.z, scene.roads);
}

std::vector<DeckLine> path_bridge_decks(const Scene& scene) {
    return bridge_decks(scene.terrain, scene.ground.z, scene.paths);
}

double DeckSurface::height(Vec2 p) const {
    if (edges.size() == 1) return deck_height((*decks)[edges[0]], p);
    // A corner of an edge's quad is that edge's (where quads overlap at a skewed junction, the
    // joint's vertex there meets the quad whose corner it is); else the nearest quad, then chord.
    const DeckLine* nearest = nullptr;
    std::tuple<bool, double, double> best{true, std::numeric_limits<double>::infinity(), 0};
    for (size_t k = 0; k < edges.size(); ++k) {
        const DeckLine& d = (*decks)[edges[k]];
        const Ring& quad = *quads[k];
        const bool corner = std::any_of(quad.begin(), quad.end(), [&](Vec2 c) { return length(c - p) < 1e-4; });
        const double to_quad = quad.size() >= 3 && !point_in_ring(p, quad) ? distance_to_boundary(p, quad) : 0;
        const Vec2 q = d.a + (d.b - d.a) * std::clamp(deck_parameter(d, p), 0.0, 1.0);
        const std::tuple<bool, double, double> distance{!corner, std::round(to_quad * 1e4), length(p - q)};  // 0.1 mm
        if (distance < best) best = distance, nearest = &d;
    }
    return nearest ? deck_height(*nearest, p) : 0.0;
}

DeckSurface edge_deck(const std::vector<DeckLine>& decks, uint32_t edge) {
    DeckSurface s;
    s.decks = &decks;
    if (edge < decks.size() && decks[edge].valid) s.edges = {edge};
    return s;
}

DeckSurface joint_deck(const Scene& scene, const std::vector<DeckLine>& decks, const Joint& joint) {
    return joint_deck_of(scene.roads, decks, joint);
}

DeckSurface path_joint_deck(const Scene& scene, const std::vector<DeckLine>& path_decks, const Joint& joint) {
    return joint_deck_of(scene.paths, path_decks, joint);
}

DeckSurface sidewalk_deck(const Scene& scene, const std::vector<DeckLine>& decks, const Sidewalk& sidewalk) {
    if (sidewalk.road >= 0) return edge_deck(decks, static_cast<uint32_t>(sidewalk.road));
    if (sidewalk.joint >= 0 && static_cast<size_t>(sidewalk.joint) < scene.joints.size())
        return joint_deck(scene, decks, scene.joints[sidewalk.joint]);
    return {};
}

double deck_parameter(const DeckLine& deck, Vec2 p) {
    const Vec2 d = deck.b - deck.a;
    const double length2 = dot(d, d);
    return length2 > 0 ? dot(p - deck.a, d) / length2 : 0.0;
}

double deck_height(const DeckLine& deck, Vec2 p) {
    const double t = std::clamp(deck_parameter(deck, p), 0.0, 1.0);
    return deck.za + (deck.zb - deck.za) * t;
}

StandingSurface::StandingSurface(const Scene& scene) : scene_(scene) {
    if (scene.terrain.empty()) return;
    // Beyond the carriageway's edge a lamp on a road bridge stands on its sidewalk or parapet;
    // beside a footbridge's or rail bridge's strip, at its railing.
    constexpr double kBeyondRoadEdge = 2.5, kBeyondPathEdge = 1;
    decks_ = bridge_decks(scene);
    for (const RoadEdge& r : scene.roads) reach_.push_back(r.width / 2 + kBeyondRoadEdge);
    for (DeckLine& d : path_bridge_decks(scene)) decks_.push_back(d);
    for (const PathEdge& p : scene.paths) reach_.push_back(p.width / 2 + kBeyondPathEdge);
    for (uint32_t e = 0; e < decks_.size(); ++e) {
        if (!decks_[e].valid) continue;
        Box2 box;
        box.extend(decks_[e].a);
        box.extend(decks_[e].b);
        const auto i0 = static_cast<int64_t>(std::floor((box.min.x - reach_[e]) / kCell));
        const auto i1 = static_cast<int64_t>(std::floor((box.max.x + reach_[e]) / kCell));
        const auto j0 = static_cast<int64_t>(std::floor((box.min.y - reach_[e]) / kCell));
        const auto j1 = static_cast<int64_t>(std::floor((box.max.y + reach_[e]) / kCell));
        if ((i1 - i0 + 1) * (j1 - j0 + 1) > kMaxCells) {  // a deck kilometres long (or a hostile scene's)
            long_decks_.push_back(e);
            continue;
        }
        for (int64_t i = i0; i <= i1; ++i)
            for (int64_t j = j0; j <= j1; ++j) cells_[cell_key(i, j)].push_back(e);
    }
}

double StandingSurface::height(Vec2 p) const {
    const double ground = ground_height(scene_, p.x, p.y);
    if (cells_.empty() && long_decks_.empty()) return ground;
    static const std::vector<uint32_t> kNone;
    const auto found = cells_.find(cell_key(static_cast<int64_t>(std::floor(p.x / kCell)),
                                            static_cast<int64_t>(std::floor(p.y / kCell))));
    const std::vector<uint32_t>& near = found == cells_.end() ? kNone : found->second;
    bool on_deck = false;
    double top = 0;
    for (const std::vector<uint32_t>* decks : {&near, &long_decks_})
        for (uint32_t e : *decks) {
            const DeckLine& d = decks_[e];
            const double t = deck_parameter(d, p);
            if (t < 0 || t > 1 || length(p - (d.a + (d.b - d.a) * t)) > reach_[e]) continue;
            const double deck = deck_height(d, p);
            top = on_deck ? std::max(top, deck) : deck;  // bridges over bridges: the upper deck
            on_deck = true;
        }
    return on_deck ? top : ground;
}

double deck_along(const DeckLine& deck, Vec2 p) {
    return deck.along_a + (deck.along_b - deck.along_a) * deck_parameter(deck, p);
}

}  // namespace citygen
