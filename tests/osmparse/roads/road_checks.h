// Invariants every road network must satisfy, shared by the fixture and real-data tests.
#pragma once

#include <gtest/gtest.h>

#include <cstdio>
#include <string>

#include "common/scene.h"
#include "osmparse/polygons/polygon_overlap.h"
#include "osmparse/polygons/ring_is_simple.h"
#include "osmparse/roads/narrow_roads.h"
#include "osmparse/roads/road_geometry.h"

namespace citygen {

struct RoadCheckCounts {
    int quads = 0, joints = 0, bad_quads = 0, bad_joints = 0, building_overlaps = 0;
    int quad_joint_overlaps = 0, quad_joint_gaps = 0, lamps_inside = 0, sidewalks_bad = 0, sidewalks_on_road = 0;
};

// Checks quads, joints, sidewalks and lamps; adds a failure per violation when `strict`
// (fixtures), and always returns the counts (real data reports them).
inline RoadCheckCounts check_road_network(const Scene& scene, bool strict_joins) {
    RoadCheckCounts c;
    const BuildingIndex buildings(scene.buildings);
    for (size_t r = 0; r < scene.roads.size(); ++r) {
        const Ring& q = scene.roads[r].quad;
        ++c.quads;
        const bool ok = q.size() == 4 && ring_is_convex(q) && signed_area(q) > 1e-3;
        if (!ok) ++c.bad_quads;
        EXPECT_TRUE(ok) << "road " << r << " (w" << scene.roads[r].osm.id << ") quad not convex/positive";
        double largest = 0;
        buildings.overlap(q, &largest);
        if (largest > kRoadBuildingOverlapTolerance) ++c.building_overlaps;
        EXPECT_LE(largest, kRoadBuildingOverlapTolerance) << "road " << r << " inside a building";
    }
    for (size_t j = 0; j < scene.joints.size(); ++j) {
        const Joint& joint = scene.joints[j];
        ++c.joints;
        const bool ok = ring_is_simple(joint.polygon) && signed_area(joint.polygon) > 0;
        if (!ok) ++c.bad_joints;
        EXPECT_TRUE(ok) << "joint n" << joint.osm.id << " not simple/CCW";
        double largest = 0;
        buildings.overlap(joint.polygon, &largest);
        if (largest > kRoadBuildingOverlapTolerance) ++c.building_overlaps;
        EXPECT_LE(largest, kRoadBuildingOverlapTolerance) << "joint n" << joint.osm.id << " inside a building";
        for (uint32_t r : joint.edges) {
            const RoadEdge& road = scene.roads.at(r);
            // No hole: just beyond the quad's end at this joint, the ground must be the
            // joint's (or another road's where near-parallel roads overlap).
            const bool at_from = road.from_joint == static_cast<int>(j);
            double gap = 0;
            for (Vec2 p : points_beyond_quad_end(road.quad, at_from)) {
                bool covered = point_in_ring(p, joint.polygon);
                for (uint32_t other : joint.edges)
                    covered = covered || (other != r && point_in_ring(p, scene.roads[other].quad));
                if (covered) continue;
                // How far the nearest surface is: the joint, or a neighbour's quad that
                // overlaps beyond it.
                double nearest = distance_to_boundary(p, joint.polygon);
                for (uint32_t other : joint.edges)
                    if (other != r) nearest = std::min(nearest, distance_to_boundary(p, scene.roads[other].quad));
                gap = std::max(gap, nearest);
            }
            const double overlap = clipped_area(joint.polygon, road.quad);
            if (gap > 0.01) ++c.quad_joint_gaps;
            if (overlap > 0.01) ++c.quad_joint_overlaps;
            if (strict_joins) {
                EXPECT_LE(gap, 0.01) << "hole beyond road " << r << " at joint n" << joint.osm.id;
                EXPECT_LE(overlap, 0.01) << "road " << r << " overlaps joint n" << joint.osm.id;
            }
        }
    }
    std::vector<Building> surface;  // road quads and joints, indexed like footprints
    for (const RoadEdge& r : scene.roads) surface.push_back({r.osm, r.quad, {}, 0, 0, 0, {}, {}, false});
    for (const Joint& j : scene.joints) surface.push_back({j.osm, j.polygon, {}, 0, 0, 0, {}, {}, false});
    const BuildingIndex surface_index(surface);
    for (const Sidewalk& s : scene.sidewalks) {
        const bool ok = ring_is_simple(s.polygon) && signed_area(s.polygon) > 0;
        if (!ok) ++c.sidewalks_bad;
        EXPECT_TRUE(ok) << "sidewalk of road " << s.road << " / joint " << s.joint << " not simple";
        double on_road = 0;
        surface_index.overlap(s.polygon, &on_road);
        // Fixtures: sidewalks exactly beside the road; real data: at most the half square
        // metre build_sidewalks allows where roads overlap each other.
        EXPECT_LE(on_road, strict_joins ? 0.01 : 0.5) << "sidewalk of road " << s.road << " / joint " << s.joint
                                                      << " on the road surface";
        if (on_road > 0.01) ++c.sidewalks_on_road;
    }
    for (const Lamp& l : scene.lamps) {
        const Vec2 p{l.position.x, l.position.y};
        bool inside = buildings.contains(p);
        for (const RoadEdge& r : scene.roads) inside = inside || point_in_ring(p, r.quad);
        for (const Joint& j : scene.joints) inside = inside || point_in_ring(p, j.polygon);
        if (inside) ++c.lamps_inside;
        EXPECT_FALSE(inside) << "lamp " << to_string(l.osm) << " at " << p.x << "," << p.y << " inside road/joint/building";
    }
    return c;
}

}  // namespace citygen
