// The road layout's working state and its passes (road_layout.cpp runs them in order;
// each junction case lives in its own file). Internal to osmparse/roads/.
#pragma once

#include <map>
#include <set>
#include <vector>

#include "osmparse/roads/road_geometry.h"
#include "osmparse/roads/road_layout.h"

namespace citygen {

inline constexpr double kMaxCutFraction = 0.45;  // no cut reaches past this share of an edge
inline constexpr double kJointsTake = 0.9;       // share of an edge the joints at its two ends may take (the rest is its quad)

// One edge as seen from the node it leaves (its origin).
struct EndGeometry {
    Vec2 origin, dir, normal;  // leaving the node; normal points left
    double half_left, half_right;
    double max_cut;
    double limit = 0;          // the furthest any cut may go before the quad would fold
    Vec2 left_at(double t) const { return origin + normal * half_left + dir * t; }
    Vec2 right_at(double t) const { return origin - normal * half_right + dir * t; }
};

// A value per edge end: at the edge's `from` node and at its `to` node.
struct PerEnd {
    std::vector<double> from, to;
    void assign(size_t n) { from.assign(n, 0), to.assign(n, 0); }
    double& at(uint32_t edge, bool at_from) { return at_from ? from[edge] : to[edge]; }
    double at(uint32_t edge, bool at_from) const { return at_from ? from[edge] : to[edge]; }
};

struct LayoutState {
    const RoadGraph& graph;
    std::vector<SideWidths> widths;
    double miter_limit = 0;
    std::vector<bool> removed;  // edges narrowing took out (they keep their index until compacted)

    // Every node with its own ends (counter-clockwise) and the join chosen for it alone.
    std::map<int64_t, NodeLayout> nodes;
    // Junctions merged from several nodes, by their smallest member; they stand in for
    // their members in the layout.
    std::map<int64_t, NodeLayout> merged;
    std::map<int64_t, int64_t> merged_into;  // member -> its merged junction

    PerEnd own_demand;  // how far each node's own joint would cut each end back (merging reads it)
    PerEnd demand;      // the same for the junction the end belongs to (merged or not)
    PerEnd fixed;       // what a miter needs of the edge
    PerEnd allowed;     // what the joint gets once each edge's length is shared out
    std::map<int64_t, std::vector<Ring>> raw_rings;  // per junction: its unfinished rings
    RoadLayout out;     // cuts, quads and absorbed edges per edge; `nodes` filled by assemble_layout

    LayoutState(const RoadGraph& g, std::vector<SideWidths> w, double limit);

    EndGeometry geometry_of(const NodeLayout::End& end) const;
    std::vector<EndGeometry> geometry_at(const NodeLayout& node) const;
    EdgeEndCut& cut_of(const NodeLayout::End& end) {
        return end.at_from ? out.from_cut[end.edge] : out.to_cut[end.edge];
    }
    double edge_length(uint32_t e) const { return length(graph.edges[e].to - graph.edges[e].from); }
    // The junction node `id` belongs to (itself, or the merged junction), or nullptr for a
    // member that is not its merged junction's key.
    NodeLayout* junction_keyed(int64_t id);
    // The junction node `node` belongs to, or nullptr when the node is gone.
    NodeLayout* junction_of(int64_t node);
    // Calls f(junction) for every junction in id order (what RoadLayout::nodes will hold).
    template <typename F>
    void for_each_junction(F&& f) {
        for (auto& [id, node] : nodes) {
            auto m = merged_into.find(id);
            if (m == merged_into.end()) f(node);
            else if (m->second == id) f(merged.at(id));
        }
    }
};

EndGeometry end_geometry(const RoadGraphEdge& e, SideWidths w, bool at_from);

// The whole layout of state.graph with state.widths.
void lay_out_all(LayoutState& state);
// After the widths of `changed` edges changed, or they were removed (state.removed):
// lays out again what depends on them, and nothing else, so the state is what
// lay_out_all would give. Returns the junctions whose joint was finished again.
std::set<int64_t> update_layout(LayoutState& state, const std::vector<uint32_t>& changed);
// The layout as a RoadLayout (RoadLayout::nodes in id order).
RoadLayout assemble_layout(LayoutState& state);
// The same, moved out of a state that is not used again (no copy of the quads and joints).
RoadLayout take_layout(LayoutState&& state);

// --- The passes, in the order road_layout.cpp runs them. ---

// Orders a node's ends counter-clockwise; in a merged junction the ends leave from
// different nodes, so the angle is taken around the centre to a point well out.
void sort_ends(const LayoutState& state, NodeLayout& node);

// Chooses how a node's own ends meet: a dead end, a miter, or a junction (its demand on
// each edge). Forgets what an earlier choice wrote for these ends first.
void choose_join(LayoutState& state, NodeLayout& node);

// dead_end.cpp: a node with one edge; the quad ends square at the node.
void lay_out_dead_end(LayoutState& state, NodeLayout& node);

// miter.cpp: a degree-2 node cut on its miter; false when the miter is not acceptable.
// `forced` (a sidewalk outline following its carriageway's miter) clamps instead.
bool lay_out_miter(LayoutState& state, NodeLayout& node, bool forced);

// junction.cpp: how far the junction would cut each end back, before sharing.
void note_junction_demand(LayoutState& state, NodeLayout& node);
// junction.cpp: the junction's cuts and unfinished rings from the shared-out lengths.
void shape_junction(LayoutState& state, NodeLayout& node);

// merged_junction.cpp: junctions closer together than their roads are wide become one
// junction; the short edges between them are absorbed. A merged junction none of whose
// members is in `touched` and whose members are the same is kept as it is; the others are
// dissolved and built again. Returns the members of those.
std::set<int64_t> merge_close_junctions(LayoutState& state, const std::set<int64_t>& touched);

// Shares edge `e`'s length between the joints at its two ends.
void share_edge_length(LayoutState& state, uint32_t e);

// Edge `e`'s quad from its cuts; empty when it would fold, is absorbed or removed.
void cut_quad(LayoutState& state, uint32_t e);

// finish_joint.cpp: the junction's joint, its quads cut out of its ring.
void finish_joint(NodeLayout& node, const std::vector<Ring>& raw_rings, const std::vector<Ring>& quads);

}  // namespace citygen
