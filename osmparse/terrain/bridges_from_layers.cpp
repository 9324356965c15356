#include "osmparse/terrain/bridges_from_layers.h"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <unordered_set>


namespace citygen {

namespace {

// A centreline segment of a road or path and its edge's layer, or a water outline's.
struct Segment {
    Vec2 a, b;
    int layer;
};

// Cells of the index the crossings are looked up in: a few edges a cell in a town.
constexpr double kCell = 64;

int64_t cell_key(int64_t i, int64_t j) { return i * 4194304 + j; }

// Calls f(key) for every cell the segment's box touches.
template <class F>
void for_each_cell(Vec2 a, Vec2 b, F&& f) {
    const auto i0 = static_cast<int64_t>(std::floor(std::fmin(a.x, b.x) / kCell));
    const auto i1 = static_cast<int64_t>(std::floor(std::fmax(a.x, b.x) / kCell));
    const auto j0 = static_cast<int64_t>(std::floor(std::fmin(a.y, b.y) / kCell));
    const auto j1 = static_cast<int64_t>(std::floor(std::fmax(a.y, b.y) / kCell));
    if ((i1 - i0 + 1) * (j1 - j0 + 1) > 4096) return;  // kilometres long: a hostile scene's, not a crossing
    for (int64_t i = i0; i <= i1; ++i)
        for (int64_t j = j0; j <= j1; ++j) f(cell_key(i, j));
}

// Strictly across each other: not touching at an end (where a ramp meets the road below).
bool cross_strictly(Vec2 a, Vec2 b, Vec2 c, Vec2 d) {
    const double o1 = cross(b - a, c - a), o2 = cross(b - a, d - a);
    const double o3 = cross(d - c, a - c), o4 = cross(d - c, b - c);
    return ((o1 < 0 && o2 > 0) || (o1 > 0 && o2 < 0)) && ((o3 < 0 && o4 > 0) || (o3 > 0 && o4 < 0));
}

}  // namespace

std::unordered_map<int64_t, int> way_layers(const OsmData& osm) {
    std::unordered_map<int64_t, int> layers;
    for (const std::vector<OsmWay>* ways : {&osm.highways, &osm.railways})
        for (const OsmWay& w : *ways) {
            const char* text = w.tags.get("layer");
            if (!text) continue;
            char* end = nullptr;
            errno = 0;
            const long layer = std::strtol(text, &end, 10);
            if (end == text || *end != '\0' || errno != 0 || layer < -5 || layer > 5 || layer == 0) continue;
            layers[w.id] = static_cast<int>(layer);
        }
    return layers;
}

void mark_layered_bridges(std::vector<RoadEdge>& roads, std::vector<PathEdge>& paths,
                          const std::unordered_map<int64_t, int>& layers, const std::vector<LandCover>& land_cover,
                          ParseReport& report) {
    if (layers.empty()) return;
    const auto layer_of = [&](const OsmRef& osm) {
        const auto found = layers.find(osm.id);
        return found == layers.end() ? 0 : found->second;
    };
    // The edges that may be bridges, and the cells they cross.
    std::vector<std::pair<bool, uint32_t>> raised;  // (is a path, index)
    std::unordered_set<int64_t> wanted;
    const auto consider = [&](bool is_path, uint32_t e, const auto& edge) {
        if (edge.bridge || layer_of(edge.osm) <= 0) return;
        raised.push_back({is_path, e});
        for (size_t k = 0; k + 1 < edge.centreline.size(); ++k)
            for_each_cell(edge.centreline[k], edge.centreline[k + 1], [&](int64_t key) { wanted.insert(key); });
    };
    for (uint32_t e = 0; e < roads.size(); ++e) consider(false, e, roads[e]);
    for (uint32_t e = 0; e < paths.size(); ++e) consider(true, e, paths[e]);
    if (raised.empty()) return;
    // What lies in those cells: every way's segments with its layer, water's outlines below all.
    std::unordered_map<int64_t, std::vector<Segment>> cells;
    const auto add = [&](Vec2 a, Vec2 b, int layer) {
        for_each_cell(a, b, [&](int64_t key) {
            if (wanted.count(key)) cells[key].push_back({a, b, layer});
        });
    };
    constexpr int kWater = -1000;
    for (const RoadEdge& r : roads)
        for (size_t k = 0; k + 1 < r.centreline.size(); ++k) add(r.centreline[k], r.centreline[k + 1], layer_of(r.osm));
    for (const PathEdge& p : paths)
        for (size_t k = 0; k + 1 < p.centreline.size(); ++k) add(p.centreline[k], p.centreline[k + 1], layer_of(p.osm));
    std::vector<const LandCover*> water;
    for (const LandCover& c : land_cover) {
        if (c.cover != LandCoverClass::Water && c.cover != LandCoverClass::Sea) continue;
        water.push_back(&c);
        for (size_t k = 0, n = c.outer.size(); k < n; ++k) add(c.outer[k], c.outer[(k + 1) % n], kWater);
    }
    int64_t marked_roads = 0, marked_paths = 0;
    for (const auto& [is_path, e] : raised) {
        const std::vector<Vec2>& line = is_path ? paths[e].centreline : roads[e].centreline;
        const int layer = layer_of(is_path ? paths[e].osm : roads[e].osm);
        bool over = false;
        for (size_t k = 0; k + 1 < line.size() && !over; ++k) {
            const Vec2 a = line[k], b = line[k + 1];
            for_each_cell(a, b, [&](int64_t key) {
                const auto found = cells.find(key);
                if (over || found == cells.end()) return;
                for (const Segment& s : found->second)
                    if (s.layer < layer && cross_strictly(a, b, s.a, s.b)) {
                        over = true;
                        return;
                    }
            });
            const Vec2 mid = (a + b) * 0.5;
            for (const LandCover* c : water)
                if (!over && point_in_ring(mid, c->outer)) over = true;
        }
        if (!over) continue;
        (is_path ? paths[e].bridge : roads[e].bridge) = true;
        ++(is_path ? marked_paths : marked_roads);
    }
    if (marked_roads > 0) report.note(ReportKind::RoadEdges, ReportReason::BridgeFromLayer, marked_roads);
    if (marked_paths > 0) report.note(ReportKind::PathEdges, ReportReason::BridgeFromLayer, marked_paths);
}

}  // namespace citygen
