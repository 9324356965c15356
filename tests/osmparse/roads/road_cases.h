// Small road graphs and the checks every road case's test shares: quads that keep their
// width, joints that are simple and meet their quads edge to edge.
#pragma once

#include <gtest/gtest.h>

#include <cmath>

#include "osmparse/polygons/polygon_overlap.h"
#include "osmparse/polygons/ring_is_simple.h"
#include "osmparse/roads/build_road_polygons.h"
#include "osmparse/roads/road_geometry.h"
#include "osmparse/roads/road_layout.h"

namespace citygen::road_cases {

inline constexpr double kMiterLimit = 2.0;  // RoadParams' default

inline RoadGraphEdge edge(int64_t from_node, int64_t to_node, Vec2 from, Vec2 to, double width = 6) {
    RoadGraphEdge e;
    e.way_id = from_node * 1000 + to_node;
    e.from_node = from_node;
    e.to_node = to_node;
    e.from = from;
    e.to = to;
    e.width = width;
    e.road_class = RoadClass::Residential;
    e.sidewalk_left = e.sidewalk_right = true;
    return e;
}

inline RoadLayout lay_out(const RoadGraph& graph) {
    return layout_road_polygons(graph, carriageway_widths(graph), kMiterLimit);
}

inline const NodeLayout& node_of(const RoadLayout& layout, int64_t id) {
    for (const NodeLayout& node : layout.nodes)
        if (node.node == id) return node;
    ADD_FAILURE() << "no node " << id;
    static const NodeLayout none;
    return none;
}

// Distance between a quad's two long sides (its right side q0-q1, its left side q2-q3).
inline double quad_width(const Ring& q) {
    return std::fabs(cross(q[1] - q[0], q[3] - q[0])) / length(q[1] - q[0]);
}

// The end corners of edge `end`'s quad at its node (right side first, as leaving the node).
inline std::pair<Vec2, Vec2> end_corners(const Ring& q, bool at_from) {
    return at_from ? std::make_pair(q[0], q[3]) : std::make_pair(q[2], q[1]);
}

// A junction's joint: simple, CCW, every quad's end on its boundary, no quad overlapping
// it, no hole just beyond any quad's end.
inline void expect_joint_meets_quads(const RoadLayout& layout, const NodeLayout& node) {
    ASSERT_EQ(node.kind, JoinKind::Joint);
    const Ring& joint = node.joint;
    ASSERT_GE(joint.size(), 3u);
    EXPECT_TRUE(ring_is_simple(joint));
    EXPECT_GT(signed_area(joint), 0);
    EXPECT_FALSE(node.joint_is_hull);
    for (const NodeLayout::End& end : node.ends) {
        const Ring& q = layout.quads[end.edge];
        ASSERT_EQ(q.size(), 4u) << "edge " << end.edge;
        const auto [right, left] = end_corners(q, end.at_from);
        EXPECT_LT(distance_to_boundary(right, joint), 1e-6) << "edge " << end.edge;
        EXPECT_LT(distance_to_boundary(left, joint), 1e-6) << "edge " << end.edge;
        EXPECT_LT(clipped_area(joint, q), kJoinOverlapTolerance) << "edge " << end.edge;
        for (Vec2 p : points_beyond_quad_end(q, end.at_from)) {
            bool covered = point_in_ring(p, joint);
            for (const NodeLayout::End& other : node.ends)
                covered = covered || (other.edge != end.edge && point_in_ring(p, layout.quads[other.edge]));
            EXPECT_TRUE(covered) << "hole beyond edge " << end.edge << " at " << p.x << "," << p.y;
        }
    }
}

// Every quad convex, CCW and as wide as its edge.
inline void expect_quads_keep_width(const RoadGraph& graph, const RoadLayout& layout) {
    for (size_t e = 0; e < graph.edges.size(); ++e) {
        if (layout.absorbed[e]) continue;
        const Ring& q = layout.quads[e];
        ASSERT_EQ(q.size(), 4u) << "edge " << e;
        EXPECT_TRUE(ring_is_convex(q)) << "edge " << e;
        EXPECT_GT(signed_area(q), 0) << "edge " << e;
        EXPECT_NEAR(quad_width(q), graph.edges[e].width, 1e-9) << "edge " << e;
    }
}

}  // namespace citygen::road_cases
