// The road layout's passes in order (each junction case is in its own file: dead_end.cpp,
// miter.cpp, junction.cpp, merged_junction.cpp, finish_joint.cpp), and the two ways to
// lay out again without starting over: an outline around a finished layout (sidewalks)
// and an update after narrowing changed some edges.
#include "osmparse/roads/road_layout.h"

#include <algorithm>
#include <cmath>

#include "osmparse/roads/layout_state.h"

namespace citygen {

LayoutState::LayoutState(const RoadGraph& g, std::vector<SideWidths> w, double limit)
    : graph(g), widths(std::move(w)), miter_limit(limit), removed(g.edges.size(), false) {
    const size_t n = graph.edges.size();
    own_demand.assign(n);
    demand.assign(n);
    fixed.assign(n);
    allowed.assign(n);
    out.from_cut.assign(n, {});
    out.to_cut.assign(n, {});
    out.quads.assign(n, {});
    out.absorbed.assign(n, false);
}

EndGeometry end_geometry(const RoadGraphEdge& e, SideWidths w, bool at_from) {
    EndGeometry g;
    const Vec2 along = at_from ? e.to - e.from : e.from - e.to;
    g.origin = at_from ? e.from : e.to;
    g.dir = normalize(along);
    g.normal = perp_left(g.dir);
    g.half_left = at_from ? w.left : w.right;
    g.half_right = at_from ? w.right : w.left;
    g.max_cut = kMaxCutFraction * length(along);
    return g;
}

EndGeometry LayoutState::geometry_of(const NodeLayout::End& end) const {
    return end_geometry(graph.edges[end.edge], widths[end.edge], end.at_from);
}

std::vector<EndGeometry> LayoutState::geometry_at(const NodeLayout& node) const {
    std::vector<EndGeometry> geo;
    for (const NodeLayout::End& end : node.ends) geo.push_back(geometry_of(end));
    return geo;
}

NodeLayout* LayoutState::junction_keyed(int64_t id) {
    auto m = merged_into.find(id);
    if (m != merged_into.end()) return m->second == id ? &merged.at(id) : nullptr;
    auto it = nodes.find(id);
    return it == nodes.end() ? nullptr : &it->second;
}

NodeLayout* LayoutState::junction_of(int64_t node) {
    auto m = merged_into.find(node);
    return junction_keyed(m == merged_into.end() ? node : m->second);
}

void sort_ends(const LayoutState& state, NodeLayout& node) {
    std::vector<std::pair<double, NodeLayout::End>> keyed;
    keyed.reserve(node.ends.size());
    for (const NodeLayout::End& end : node.ends) {
        const EndGeometry g = state.geometry_of(end);
        const Vec2 far = g.origin - node.position + g.dir * 50.0;
        keyed.emplace_back(std::atan2(far.y, far.x), end);
    }
    std::sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) {
        if (a.first != b.first) return a.first < b.first;
        return a.second.edge != b.second.edge ? a.second.edge < b.second.edge : a.second.at_from < b.second.at_from;
    });
    for (size_t i = 0; i < keyed.size(); ++i) node.ends[i] = std::move(keyed[i].second);
}

namespace {

// Forgets what an earlier layout of this node wrote, so an update lays it out afresh.
void forget_join(LayoutState& state, NodeLayout& node) {
    node.joint.clear();
    node.joint_is_hull = false;
    for (NodeLayout::End& end : node.ends) {
        end.trim = end.cut_left = end.cut_right = 0;
        end.gap_points.clear();
        state.cut_of(end) = {};
        state.fixed.at(end.edge, end.at_from) = 0;
        state.demand.at(end.edge, end.at_from) = 0;
        state.own_demand.at(end.edge, end.at_from) = 0;
    }
}

// The join a sidewalk outline takes: the one its carriageway chose (a miter is forced to fit).
void follow_join(LayoutState& state, NodeLayout& node, JoinKind kind) {
    forget_join(state, node);
    if (kind == JoinKind::End) {
        lay_out_dead_end(state, node);
        return;
    }
    if (kind == JoinKind::Miter && lay_out_miter(state, node, true)) return;
    note_junction_demand(state, node);
}

// Every node with the ends of the edges meeting there, counter-clockwise, and its join.
void collect_nodes(LayoutState& state) {
    const RoadGraph& graph = state.graph;
    // The map's entries are made in id order first: every pass walks the map in that order,
    // and entries made in edge order would lie scattered over the heap.
    std::vector<int64_t> ids;
    ids.reserve(2 * graph.edges.size());
    for (uint32_t e = 0; e < graph.edges.size(); ++e)
        if (!state.removed[e]) ids.insert(ids.end(), {graph.edges[e].from_node, graph.edges[e].to_node});
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    for (int64_t id : ids) state.nodes.emplace_hint(state.nodes.end(), id, NodeLayout{});
    for (uint32_t e = 0; e < graph.edges.size(); ++e) {
        if (state.removed[e]) continue;
        const RoadGraphEdge& edge = graph.edges[e];
        NodeLayout& a = state.nodes[edge.from_node];
        a.node = edge.from_node;
        a.position = edge.from;
        a.ends.push_back({e, true, edge.from, 0, 0, 0, {}});
        NodeLayout& b = state.nodes[edge.to_node];
        b.node = edge.to_node;
        b.position = edge.to;
        b.ends.push_back({e, false, edge.to, 0, 0, 0, {}});
    }
    for (auto& [id, node] : state.nodes) {
        sort_ends(state, node);
        choose_join(state, node);
    }
}

bool quad_is_valid(const Ring& q) {
    return q.size() == 4 && ring_is_convex(q) && signed_area(q) > 1e-3;
}

// Shares out every edge's length, then shapes, cuts and finishes everything.
void shape_everything(LayoutState& state) {
    const uint32_t n = static_cast<uint32_t>(state.graph.edges.size());
    for (uint32_t e = 0; e < n; ++e) share_edge_length(state, e);
    state.for_each_junction([&](NodeLayout& node) {
        if (node.kind == JoinKind::Joint && !node.ends.empty()) shape_junction(state, node);
    });
    for (uint32_t e = 0; e < n; ++e) cut_quad(state, e);
    state.for_each_junction([&](NodeLayout& node) {
        if (node.kind == JoinKind::Joint && !node.ends.empty())
            finish_joint(node, state.raw_rings[node.node], state.out.quads);
    });
}

}  // namespace

void choose_join(LayoutState& state, NodeLayout& node) {
    forget_join(state, node);
    const size_t k = node.ends.size();
    if (k == 1) {
        lay_out_dead_end(state, node);
        return;
    }
    if (k == 2 && lay_out_miter(state, node, false)) return;
    note_junction_demand(state, node);
    for (const NodeLayout::End& end : node.ends)
        state.own_demand.at(end.edge, end.at_from) = state.demand.at(end.edge, end.at_from);
}

void share_edge_length(LayoutState& state, uint32_t e) {
    // Each edge's length is shared between the joints at its two ends, keeping 10% of it
    // (and whatever a miter at either end needs) for the quad.
    const double len = state.edge_length(e);
    const double room = std::max(0.0, kJointsTake * len - state.fixed.from[e] - state.fixed.to[e]);
    const double wanted = state.demand.from[e] + state.demand.to[e];
    const double scale = wanted > room ? room / wanted : 1.0;
    state.allowed.from[e] = state.demand.from[e] * scale;
    state.allowed.to[e] = state.demand.to[e] * scale;
}

void cut_quad(LayoutState& state, uint32_t e) {
    state.out.quads[e].clear();
    if (state.removed[e] || state.out.absorbed[e]) return;
    Ring q = quad_for_cuts(state.graph.edges[e], state.widths[e], state.out.from_cut[e], state.out.to_cut[e]);
    if (quad_is_valid(q)) state.out.quads[e] = std::move(q);
}

void lay_out_all(LayoutState& state) {
    collect_nodes(state);
    merge_close_junctions(state, {});
    shape_everything(state);
}

RoadLayout assemble_layout(LayoutState& state) {
    RoadLayout out = state.out;
    out.nodes.clear();
    state.for_each_junction([&](NodeLayout& node) { out.nodes.push_back(node); });
    return out;
}

size_t quad_count(const RoadLayout& layout) {
    size_t count = 0;
    for (size_t e = 0; e < layout.quads.size(); ++e) count += !layout.absorbed[e] && !layout.quads[e].empty();
    return count;
}

size_t joint_count(const RoadLayout& layout) {
    size_t count = 0;
    for (const NodeLayout& node : layout.nodes) count += node.kind == JoinKind::Joint && !node.joint.empty();
    return count;
}

RoadLayout take_layout(LayoutState&& state) {
    RoadLayout out = std::move(state.out);
    out.nodes.clear();
    size_t count = 0;
    state.for_each_junction([&](NodeLayout&) { ++count; });
    out.nodes.reserve(count);  // exactly: the layouts are kept while the later road stages run
    state.for_each_junction([&](NodeLayout& node) { out.nodes.push_back(std::move(node)); });
    return out;
}

Ring quad_for_cuts(const RoadGraphEdge& e, SideWidths w, EdgeEndCut from, EdgeEndCut to) {
    const Vec2 d = normalize(e.to - e.from), n = perp_left(d);
    return {e.from - n * w.right + d * from.t_right, e.to - n * w.right - d * to.t_left,
            e.to + n * w.left - d * to.t_right, e.from + n * w.left + d * from.t_left};
}

RoadLayout layout_road_polygons(const RoadGraph& graph, const std::vector<SideWidths>& widths, double miter_limit) {
    LayoutState state(graph, widths, miter_limit);
    lay_out_all(state);
    return take_layout(std::move(state));
}

RoadLayout lay_out_outline(const RoadGraph& graph, RoadLayout carriageway,
                           const std::vector<SideWidths>& widths, double miter_limit) {
    LayoutState state(graph, widths, miter_limit);
    state.out.absorbed = std::move(carriageway.absorbed);
    for (NodeLayout& node : carriageway.nodes) {
        const JoinKind kind = node.kind;
        NodeLayout& moved = state.nodes[node.node] = std::move(node);
        follow_join(state, moved, kind);
    }
    carriageway = {};  // its nodes are the outline's now
    shape_everything(state);
    return take_layout(std::move(state));
}

namespace {

// Update step 1: the nodes at the changed edges get their ends (less removed edges) and
// their own join again. Returns those nodes.
std::set<int64_t> rejoin_nodes_at(LayoutState& state, const std::vector<uint32_t>& changed) {
    std::set<int64_t> touched;
    for (uint32_t e : changed) {
        touched.insert(state.graph.edges[e].from_node);
        touched.insert(state.graph.edges[e].to_node);
    }
    for (int64_t v : touched) {
        auto it = state.nodes.find(v);
        if (it == state.nodes.end()) continue;
        std::vector<NodeLayout::End>& ends = it->second.ends;
        ends.erase(std::remove_if(ends.begin(), ends.end(), [&](const NodeLayout::End& end) { return state.removed[end.edge]; }),
                   ends.end());
        if (ends.empty()) {
            state.raw_rings.erase(v);
            state.nodes.erase(it);
            continue;
        }
        sort_ends(state, it->second);
        choose_join(state, it->second);
    }
    return touched;
}

// The junctions at the two ends of edge `e` into `keys`.
void add_junctions_at(LayoutState& state, uint32_t e, std::set<int64_t>& keys) {
    for (int64_t v : {state.graph.edges[e].from_node, state.graph.edges[e].to_node})
        if (NodeLayout* j = state.junction_of(v)) keys.insert(j->node);
}

// Update step 3: the length of every edge at the `reshaped` junctions is shared out
// again; where an edge's share changes, the junction at its other end is added (its
// joint may reach further along that edge now).
void reshare_lengths(LayoutState& state, std::set<int64_t>& reshaped) {
    std::set<uint32_t> shared;
    for (int64_t key : reshaped)
        for (const NodeLayout::End& end : state.junction_keyed(key)->ends) shared.insert(end.edge);
    std::set<int64_t> neighbours;
    for (uint32_t e : shared) {
        const double before[4] = {state.allowed.from[e], state.allowed.to[e], state.fixed.from[e], state.fixed.to[e]};
        share_edge_length(state, e);
        const double after[4] = {state.allowed.from[e], state.allowed.to[e], state.fixed.from[e], state.fixed.to[e]};
        if (!std::equal(before, before + 4, after)) add_junctions_at(state, e, neighbours);
    }
    reshaped.insert(neighbours.begin(), neighbours.end());
}

}  // namespace

std::set<int64_t> update_layout(LayoutState& state, const std::vector<uint32_t>& changed) {
    const std::set<int64_t> touched = rejoin_nodes_at(state, changed);
    // 2. Merged junctions that changed are dissolved and built again.
    const std::set<int64_t> regrouped = merge_close_junctions(state, touched);
    std::set<int64_t> reshaped;  // junction keys whose own layout is redone
    for (const std::set<int64_t>& nodes : {touched, regrouped})
        for (int64_t v : nodes)
            if (NodeLayout* j = state.junction_of(v)) reshaped.insert(j->node);
    reshare_lengths(state, reshaped);
    // 4. Those junctions are shaped again; the quads at them (and those of edges absorbed
    // or freed by a merged junction) are cut again; every junction whose ring or quads
    // changed is finished again.
    std::set<uint32_t> recut(changed.begin(), changed.end());
    for (int64_t key : reshaped) {
        NodeLayout& node = *state.junction_keyed(key);
        if (node.kind == JoinKind::Joint) shape_junction(state, node);
        for (const NodeLayout::End& end : node.ends) recut.insert(end.edge);
    }
    for (int64_t v : regrouped)
        if (auto it = state.nodes.find(v); it != state.nodes.end())
            for (const NodeLayout::End& end : it->second.ends) recut.insert(end.edge);
    std::set<int64_t> refinish = reshaped;
    for (uint32_t e : recut) {
        const Ring before = state.out.quads[e];
        cut_quad(state, e);
        if (state.out.quads[e] != before) add_junctions_at(state, e, refinish);
    }
    for (int64_t key : refinish) {
        NodeLayout& node = *state.junction_keyed(key);
        if (node.kind == JoinKind::Joint && !node.ends.empty())
            finish_joint(node, state.raw_rings[node.node], state.out.quads);
    }
    return refinish;
}

}  // namespace citygen
