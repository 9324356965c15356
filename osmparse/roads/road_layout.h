// The geometric core shared by carriageways and sidewalks: given straight edges with a
// half width on each side, cut every edge to a quadrangle and build the polygon of every
// junction (as in the thesis named in README, made robust for real data).
#pragma once

#include <cstdint>
#include <vector>

#include "common/geometry.h"
#include "osmparse/roads/build_road_graph.h"

namespace citygen {

// Half widths of an edge to the left and right of its from -> to direction.
struct SideWidths {
    double left = 0, right = 0;
};

// How the edges at a node meet.
enum class JoinKind : uint8_t {
    End,    // a dead end (degree 1): the quad ends square at the node
    Miter,  // degree 2: the two quads meet on the line through their offset-line intersections
    Joint,  // degree >= 3, or a degree-2 turn too sharp for a miter: a joint polygon
};

// Where an edge's quad starts, measured from the node along the edge, on the left and
// right side of the direction leaving the node. Negative on the outside of a miter.
struct EdgeEndCut {
    double t_left = 0, t_right = 0;
};

struct NodeLayout {
    int64_t node = 0;               // the smallest id of `members` for a merged junction
    std::vector<int64_t> members;   // nodes merged into this junction; empty for a plain node
    Vec2 position;                  // the node, or the centre of the merged nodes
    JoinKind kind = JoinKind::End;
    struct End {
        uint32_t edge = 0;
        bool at_from = true;          // the edge leaves this node at its `from` end
        Vec2 origin;                  // the node it leaves (differs from `position` in merged junctions)
        double trim = 0;              // how far the joint reaches along the edge
        double cut_left = 0, cut_right = 0;  // where the quad starts on each side (equal but
                                             // for a common cut shared with a near-parallel neighbour)
        std::vector<Vec2> gap_points; // boundary between this end's left side and the next end's right side
    };
    std::vector<End> ends;  // counter-clockwise by direction leaving the node
    Ring joint;             // CCW; empty when kind != Joint or nothing was left of it
    bool joint_is_hull = false;  // the exact polygon did not fit its quads; a star-shaped
                                 // ordering of its points (or their convex hull) stands in
};

struct RoadLayout {
    std::vector<EdgeEndCut> from_cut, to_cut;  // per edge
    std::vector<Ring> quads;                    // per edge, CCW; empty when it would fold or is absorbed
    std::vector<bool> absorbed;                 // per edge: inside a merged junction
    std::vector<NodeLayout> nodes;              // sorted by node id
};

// The edges that keep a quad (neither absorbed nor folded) and the nodes that have a joint:
// what the road and path surfaces are built from.
size_t quad_count(const RoadLayout& layout);
size_t joint_count(const RoadLayout& layout);

// Lays out every edge of `graph` with the given half widths (osmparse/roads/ has one file
// per case: dead_end.cpp, miter.cpp, junction.cpp, merged_junction.cpp, finish_joint.cpp).
// A degree-2 node gets a miter when both offset-line intersections lie within
// miter_limit half widths of the node and cut neither edge beyond 45% of its length;
// otherwise it is treated like a junction. Each edge's length is shared between the cuts
// at its two ends, keeping 10% for the quad, so quads never fold. Junctions joined by an
// edge shorter than their joints need (within 25 m) are merged into one joint polygon and
// the edge is absorbed; near-parallel neighbours share one cut line (across the bisector,
// or one end's cut carried across the other where a short edge cannot reach that far).
// Joints are finished once every quad is known: the quads of a joint's ends are cut out
// of it, so quad and joint meet edge to edge; what a tangle of short edges still leaves
// (a hole or overlap) is counted by build_road_polygons.
RoadLayout layout_road_polygons(const RoadGraph& graph, const std::vector<SideWidths>& widths, double miter_limit);

// An outline around a finished layout (sidewalks follow their carriageway): the same
// nodes, ends, joins and merged junctions as `carriageway`, shaped again with the wider
// `widths` (a miter is kept, clamped to fit). The carriageway's nodes are taken over (the
// sidewalks pass theirs in, moved: one copy of the nodes, not two, at their peak).
RoadLayout lay_out_outline(const RoadGraph& graph, RoadLayout carriageway,
                           const std::vector<SideWidths>& widths, double miter_limit);

// The four corners of edge `e`'s quad for the given cuts, CCW: right side from -> to,
// then the left side back.
Ring quad_for_cuts(const RoadGraphEdge& e, SideWidths w, EdgeEndCut from, EdgeEndCut to);

}  // namespace citygen
