#include "render/geometry/road_markings.h"

#include <cmath>

#include "common/rng.h"
#include "render/geometry/surface_detail.h"
#include "render/materials/materials.h"

namespace citygen {

namespace {

constexpr double kLine = 0.12, kEdgeLine = 0.15, kDash = 3, kDashPeriod = 9;

bool dashed_on(double along) {
    const double phase = along - kDashPeriod * std::floor(along / kDashPeriod);
    return phase < kDash;
}

}  // namespace

uint16_t asphalt_grain(Vec2 p) {
    const int64_t x = static_cast<int64_t>(std::floor(p.x / 0.04)), y = static_cast<int64_t>(std::floor(p.y / 0.04));
    return hash_to_unit(hash_keys(0x5eed, static_cast<uint64_t>(x), static_cast<uint64_t>(y))) < 0.2 ? kAsphaltLight
                                                                                                      : kAsphalt;
}

RoadPaint road_paint(const RoadEdge& road) {
    RoadPaint paint;
    paint.straight = road.centreline.size() >= 2;
    if (paint.straight) paint.a = road.centreline.front(), paint.b = road.centreline.back();
    paint.width = road.width;
    paint.lanes_forward = road.lanes_forward;
    paint.lanes_backward = road.lanes_backward;
    paint.centre_line = road.centre_line;
    paint.edge_lines = road.edge_lines;
    paint.cycle_lane_left = road.cycle_lane_left;
    paint.cycle_lane_right = road.cycle_lane_right;
    return paint;
}

uint16_t road_surface_material(const RoadPaint& road, const std::vector<const Crossing*>& crossings, Vec2 p) {
    if (!road.straight) return asphalt_grain(p);
    const Vec2 a = road.a, d = normalize(road.b - a), n = perp_left(d);
    const double along = dot(p - a, d), across = dot(p - a, n);
    const double half = 0.5 * road.width;

    for (const Crossing* c : crossings) {
        const double ca = dot(p - c->position, d), cx = dot(p - c->position, n);
        if (c->kind == CrossingKind::Zebra) {
            if (std::fabs(ca) <= 1.5 && std::fabs(cx) <= half - 0.3) {
                const double stripe = (cx + half) / 0.5;
                if ((static_cast<int64_t>(std::floor(stripe)) & 1) == 0) return kPaintWhite;
                return asphalt_grain(p);  // no lane lines through a zebra
            }
        } else if (std::fabs(ca) <= 0.2) {
            const bool side_ok = c->side == RoadSide::Both || (c->side == RoadSide::Right ? cx <= 0 : cx >= 0);
            if (side_ok && std::fabs(cx) <= half - 0.3) return kPaintWhite;
        }
    }

    // Cycle lanes: 1.5 m at the edge, behind a solid line; the motor lanes share the rest.
    constexpr double kCycleLane = 1.5;
    const double right_edge = -half + (road.cycle_lane_right ? kCycleLane : 0);
    const double left_edge = half - (road.cycle_lane_left ? kCycleLane : 0);
    if ((road.cycle_lane_right && std::fabs(across - right_edge) <= 0.5 * kEdgeLine) ||
        (road.cycle_lane_left && std::fabs(across - left_edge) <= 0.5 * kEdgeLine))
        return kPaintWhite;
    const int lanes = road.lanes_forward + road.lanes_backward;
    if (lanes > 0 && left_edge > right_edge) {
        const double lane_width = (left_edge - right_edge) / lanes;
        // Right-hand traffic: forward lanes on the right (across < 0).
        const double split = right_edge + road.lanes_forward * lane_width;
        const double to_split = std::fabs(across - split);
        switch (road.centre_line) {
            case CentreLine::Dashed:
                if (to_split <= 0.5 * kLine && dashed_on(along)) return kPaintWhite;
                break;
            case CentreLine::Solid:
                if (to_split <= 0.5 * kLine) return kPaintWhite;
                break;
            case CentreLine::Double:
                if (std::fabs(to_split - 0.12) <= 0.5 * kLine) return kPaintWhite;
                break;
            case CentreLine::None: break;
        }
        // Dividers between lanes of one direction.
        for (int k = 1; k < lanes; ++k) {
            if (k == road.lanes_forward) continue;  // the centre line's place
            if (std::fabs(across - (right_edge + k * lane_width)) <= 0.5 * kLine && dashed_on(along)) return kPaintWhite;
        }
        if (road.edge_lines && std::fabs(std::fabs(across) - (half - 0.3)) <= 0.5 * kEdgeLine) return kPaintWhite;
    }
    return asphalt_grain(p);
}

std::unique_ptr<RenderGeometry> with_road_markings(std::unique_ptr<RenderGeometry> roads, const Scene& scene) {
    // The decorator keeps its own copy of what it paints from (the scene may go first).
    struct Paint {
        std::vector<RoadPaint> roads;
        std::vector<Crossing> crossings;
        std::vector<std::vector<const Crossing*>> per_road;
    };
    auto paint = std::make_shared<Paint>();
    paint->roads.reserve(scene.roads.size());
    for (const RoadEdge& r : scene.roads) paint->roads.push_back(road_paint(r));
    paint->crossings = scene.crossings;
    paint->per_road.resize(scene.roads.size());
    for (const Crossing& c : paint->crossings)
        if (c.road >= 0 && static_cast<size_t>(c.road) < paint->roads.size()) paint->per_road[c.road].push_back(&c);
    return std::make_unique<SurfaceDetailGeometry>(std::move(roads), [paint](Hit& hit) {
        if (hit.material != kAsphalt || hit.object >= paint->roads.size()) return;
        hit.material = road_surface_material(paint->roads[hit.object], paint->per_road[hit.object],
                                             {hit.position.x, hit.position.y});
    });
}

std::unique_ptr<RenderGeometry> with_asphalt_grain(std::unique_ptr<RenderGeometry> joints) {
    return std::make_unique<SurfaceDetailGeometry>(std::move(joints), [](Hit& hit) {
        if (hit.material == kAsphalt) hit.material = asphalt_grain({hit.position.x, hit.position.y});
    });
}

}  // namespace citygen
