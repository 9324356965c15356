#include "osmparse/terrain/fill_dem_voids.h"

#include <algorithm>
#include <cmath>
#include <deque>

#include "common/error.h"
#include "common/scene_limits.h"

namespace citygen {

namespace {

enum class NodeState : uint8_t { Known, Void, Queued, Outside };  // Queued: in fill_from_rim's next layer

// Calls f(neighbour index) for the up to 8 neighbours of node k.
template <typename F>
void for_each_neighbour(const DemGrid& g, size_t k, F&& f) {
    const int64_t i = static_cast<int64_t>(k % g.nx), j = static_cast<int64_t>(k / g.nx);
    for (int64_t dj = -1; dj <= 1; ++dj)
        for (int64_t di = -1; di <= 1; ++di) {
            const int64_t ni = i + di, nj = j + dj;
            if ((di || dj) && ni >= 0 && nj >= 0 && ni < g.nx && nj < g.ny)
                f(static_cast<size_t>(nj * g.nx + ni));
        }
}

// Calls f(neighbour index) for the up to 4 edge neighbours of node k.
template <typename F>
void for_each_edge_neighbour(const DemGrid& g, size_t k, F&& f) {
    const size_t i = k % g.nx, j = k / g.nx;
    if (i > 0) f(k - 1);
    if (i + 1 < g.nx) f(k + 1);
    if (j > 0) f(k - g.nx);
    if (j + 1 < g.ny) f(k + g.nx);
}

// Known, void or outside; a void in the scene's sea is sea level at once.
std::vector<NodeState> classify(DemGrid& g, const std::vector<uint8_t>& sea, VoidCounts& counts) {
    std::vector<NodeState> state(g.size());
    for (size_t k = 0; k < g.size(); ++k) {
        const float h = g.heights[k];
        if (!g.covered[k]) {
            state[k] = NodeState::Outside;
            ++counts.outside;
        } else if (altitude_within_limit(h)) {
            state[k] = NodeState::Known;
        } else {
            counts.out_of_range += std::isfinite(h);
            if (!sea.empty() && sea[k]) {
                g.heights[k] = 0;
                state[k] = NodeState::Known;
                ++counts.sea;
            } else {
                state[k] = NodeState::Void;
            }
        }
    }
    return state;
}

// The 8-connected region of void nodes that holds `seed`, each node marked in `seen`.
std::vector<size_t> void_region(const DemGrid& g, const std::vector<NodeState>& state, size_t seed,
                                std::vector<uint8_t>& seen) {
    std::vector<size_t> region{seed};
    seen[seed] = 1;
    for (size_t n = 0; n < region.size(); ++n)
        for_each_neighbour(g, region[n], [&](size_t m) {
            if (state[m] == NodeState::Void && !seen[m]) {
                seen[m] = 1;
                region.push_back(m);
            }
        });
    return region;
}

// The known nodes around a region: how many, and how many of them at sea level.
struct RegionRim {
    size_t nodes = 0, at_sea_level = 0;
    bool at_coast() const { return nodes > 0 && 2 * at_sea_level >= nodes; }
};
RegionRim region_rim(const DemGrid& g, const std::vector<NodeState>& state, const std::vector<size_t>& region) {
    std::vector<size_t> rim;
    for (size_t k : region)
        for_each_neighbour(g, k, [&](size_t m) { if (state[m] == NodeState::Known) rim.push_back(m); });
    std::sort(rim.begin(), rim.end());
    rim.erase(std::unique(rim.begin(), rim.end()), rim.end());
    RegionRim out;
    out.nodes = rim.size();
    for (size_t m : rim) out.at_sea_level += g.heights[m] >= kCoastRimMin && g.heights[m] <= kCoastRimMax;
    return out;
}

// Fills the region layer by layer from its rim, each node the mean of its known neighbours
// (those of the layers before), then relaxes it towards the harmonic fill (each node the mean
// of its 4 neighbours), which a plane satisfies: a slope continues through the hole.
void fill_from_rim(DemGrid& g, std::vector<NodeState>& state, const std::vector<size_t>& region) {
    std::vector<size_t> layer;
    for (size_t k : region) {
        bool next_to_known = false;
        for_each_neighbour(g, k, [&](size_t m) { next_to_known = next_to_known || state[m] == NodeState::Known; });
        if (next_to_known) layer.push_back(k);
    }
    for (size_t k : layer) state[k] = NodeState::Queued;
    while (!layer.empty()) {
        std::vector<float> values;
        for (size_t k : layer) {
            double sum = 0;
            int n = 0;
            for_each_neighbour(g, k, [&](size_t m) {
                if (state[m] == NodeState::Known) sum += g.heights[m], ++n;
            });
            values.push_back(static_cast<float>(sum / n));
        }
        std::vector<size_t> next;
        for (size_t n = 0; n < layer.size(); ++n) {
            g.heights[layer[n]] = values[n];
            state[layer[n]] = NodeState::Known;
        }
        for (size_t k : layer)
            for_each_neighbour(g, k, [&](size_t m) {
                if (state[m] == NodeState::Void) state[m] = NodeState::Queued, next.push_back(m);
            });
        layer = std::move(next);
    }
    constexpr int kMaxSweeps = 200;
    constexpr double kSettled = 1e-3;  // metres: a sweep that moves no node more than this ends it
    for (int sweep = 0; sweep < kMaxSweeps; ++sweep) {
        double largest_change = 0;
        for (size_t k : region) {
            double sum = 0;
            int n = 0;
            for_each_edge_neighbour(g, k, [&](size_t m) { if (state[m] == NodeState::Known) sum += g.heights[m], ++n; });
            const float h = static_cast<float>(sum / n);
            largest_change = std::fmax(largest_change, std::fabs(h - g.heights[k]));
            g.heights[k] = h;
        }
        if (largest_change < kSettled) break;
    }
}

// Every node still without a height takes that of the nearest node with one (breadth first over
// edge neighbours: nearest in steps along the grid, ties to the lower index, every run the same).
void extend_to_outside(DemGrid& g, std::vector<NodeState>& state) {
    std::deque<size_t> queue;
    for (size_t k = 0; k < g.size(); ++k)
        if (state[k] == NodeState::Known) {
            bool borders = false;
            for_each_edge_neighbour(g, k, [&](size_t m) { borders = borders || state[m] != NodeState::Known; });
            if (borders) queue.push_back(k);
        }
    for (; !queue.empty(); queue.pop_front())
        for_each_edge_neighbour(g, queue.front(), [&](size_t m) {
            if (state[m] == NodeState::Known) return;
            g.heights[m] = g.heights[queue.front()];
            state[m] = NodeState::Known;
            queue.push_back(m);
        });
}

}  // namespace

VoidCounts fill_dem_voids(DemGrid& grid, const std::vector<uint8_t>& sea) {
    VoidCounts counts;
    std::vector<NodeState> state = classify(grid, sea, counts);
    std::vector<uint8_t> seen(grid.size(), 0);
    for (size_t k = 0; k < grid.size(); ++k) {
        if (state[k] != NodeState::Void || seen[k]) continue;
        const std::vector<size_t> region = void_region(grid, state, k, seen);
        const RegionRim rim = region_rim(grid, state, region);
        if (rim.at_coast()) {
            for (size_t m : region) grid.heights[m] = 0, state[m] = NodeState::Known;
            counts.sea += static_cast<int64_t>(region.size());
        } else {
            // A region with nothing known beside it lies between DEMs: the nearest height, as outside.
            if (rim.nodes > 0) fill_from_rim(grid, state, region);
            else for (size_t m : region) state[m] = NodeState::Outside;
            counts.filled += static_cast<int64_t>(region.size());
        }
    }
    bool any_known = false;
    for (NodeState s : state) any_known = any_known || s == NodeState::Known;
    if (!any_known) throw Error("the DEM holds no valid height over the extract (every cell is no data)");
    extend_to_outside(grid, state);
    return counts;
}

}  // namespace citygen
