// Merged junction: junctions joined by an edge shorter than their joints need become one
// junction (osm2streets merges short roads the same way). The short edges between them
// are absorbed; the junction's ends are every other end of its members, sorted around
// their centre, and it is then shaped like any junction (junction.cpp).
#include <algorithm>

#include "osmparse/roads/layout_state.h"

namespace citygen {

namespace {

constexpr double kMaxJunctionSpan = 25;  // metres: junctions merged into one joint stay this small

// Which nodes belong together: an edge whose two junctions would cut away more of it
// than the joints may take joins its ends, as long as the merged junction stays within
// kMaxJunctionSpan. Sets every edge's `absorbed` flag.
std::map<int64_t, std::vector<int64_t>> group_close_junctions(LayoutState& state) {
    const RoadGraph& graph = state.graph;
    NodeUnionFind groups;
    std::map<int64_t, std::vector<Vec2>> positions;  // of the nodes in each group, by root
    for (uint32_t e = 0; e < graph.edges.size(); ++e) {
        if (state.removed[e]) continue;
        const RoadGraphEdge& edge = graph.edges[e];
        // The cheap test first: most edges are long enough for their joints (no node lookups).
        if (state.own_demand.from[e] + state.own_demand.to[e] <= kJointsTake * state.edge_length(e)) continue;
        if (state.nodes.at(edge.from_node).kind != JoinKind::Joint || state.nodes.at(edge.to_node).kind != JoinKind::Joint) continue;
        const int64_t a = groups.root(edge.from_node), b = groups.root(edge.to_node);
        if (a == b) continue;
        std::vector<Vec2> pa = positions.count(a) ? positions[a] : std::vector<Vec2>{edge.from};
        std::vector<Vec2> pb = positions.count(b) ? positions[b] : std::vector<Vec2>{edge.to};
        double span = 0;
        for (Vec2 p : pa)
            for (Vec2 q : pb) span = std::max(span, length(p - q));
        if (span > kMaxJunctionSpan) continue;
        groups.join(a, b);
        pa.insert(pa.end(), pb.begin(), pb.end());
        positions[std::min(a, b)] = pa;
    }
    for (uint32_t e = 0; e < graph.edges.size(); ++e)
        state.out.absorbed[e] = !state.removed[e] && groups.joined(graph.edges[e].from_node) &&
                                groups.root(graph.edges[e].from_node) == groups.root(graph.edges[e].to_node);
    return groups.sets();
}

// One junction standing in for `members` (ascending; the first is its key).
NodeLayout merge_junction(LayoutState& state, const std::vector<int64_t>& members) {
    NodeLayout merged;
    merged.node = members.front();
    merged.kind = JoinKind::Joint;
    merged.members = members;
    Vec2 sum;
    for (int64_t m : members) {
        const NodeLayout& node = state.nodes.at(m);
        sum = sum + node.position;
        for (const NodeLayout::End& end : node.ends) {
            if (state.out.absorbed[end.edge]) continue;
            merged.ends.push_back(end);
            state.fixed.at(end.edge, end.at_from) = 0;
        }
    }
    merged.position = sum * (1.0 / members.size());
    sort_ends(state, merged);
    note_junction_demand(state, merged);
    return merged;
}

}  // namespace

std::set<int64_t> merge_close_junctions(LayoutState& state, const std::set<int64_t>& touched) {
    const std::map<int64_t, std::vector<int64_t>> groups = group_close_junctions(state);
    // A merged junction is kept as it is when the same nodes still form it and none of
    // them changed; the others are dissolved and (re)built.
    auto unchanged = [&](int64_t key, const std::vector<int64_t>& members) {
        auto it = state.merged.find(key);
        if (it == state.merged.end() || it->second.members != members) return false;
        return std::none_of(members.begin(), members.end(), [&](int64_t m) { return touched.count(m) > 0; });
    };
    std::set<int64_t> regrouped;
    for (auto it = state.merged.begin(); it != state.merged.end();) {
        auto g = groups.find(it->first);
        if (g != groups.end() && unchanged(g->first, g->second)) {
            ++it;
            continue;
        }
        for (int64_t m : it->second.members) {
            regrouped.insert(m);
            state.merged_into.erase(m);
        }
        it = state.merged.erase(it);
    }
    std::vector<const std::vector<int64_t>*> to_build;
    for (const auto& [key, members] : groups) {
        if (state.merged.count(key)) continue;
        regrouped.insert(members.begin(), members.end());
        to_build.push_back(&members);
    }
    // Members go back to their own join first (the merged junction rewrites what it
    // takes over), so a node leaving a merged junction is laid out as if it never was.
    for (int64_t m : regrouped) {
        auto it = state.nodes.find(m);
        if (it != state.nodes.end()) choose_join(state, it->second);
    }
    for (const std::vector<int64_t>* members : to_build) {
        for (int64_t m : *members) state.merged_into[m] = members->front();
        state.merged[members->front()] = merge_junction(state, *members);
    }
    return regrouped;
}

}  // namespace citygen
