#include "osmparse/map/place_lamps.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <optional>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "common/rng.h"
#include "common/scene_limits.h"
#include "osmparse/buildings/build_buildings.h"
#include "osmparse/core/osm_units.h"
#include "osmparse/map/point_placement.h"
#include "osmparse/polygons/polygon_overlap.h"
#include "osmparse/read/read_osm.h"

namespace citygen {

namespace {

constexpr double kKerbOffset = 0.5;  // metres beyond the carriageway edge
constexpr double kMinTaggedHeight = 2, kMaxTaggedHeight = 30;

// Where a lamp may not stand (road surfaces and buildings) and the ground it stands on (a
// sidewalk's curb or the street).
class LampObstacles {
public:
    explicit LampObstacles(const Scene& scene) : scene_(scene) {
        tbb::parallel_invoke([&] { buildings_.emplace(scene.buildings); },
                             [&] { surface_.emplace(surface_polygons(scene.roads, scene.joints)); },
                             [&] {
                                 std::vector<PolygonRef> walk_pieces;
                                 walk_pieces.reserve(scene.sidewalks.size());
                                 for (const Sidewalk& s : scene.sidewalks) walk_pieces.push_back({&s.polygon});
                                 sidewalks_.emplace(std::move(walk_pieces));
                             });
    }

    // The first surface piece (in index order) containing p.
    const Ring* surface_containing(Vec2 p) const {
        Box2 box;
        box.extend(p);
        uint32_t first = UINT32_MAX;
        surface_->for_each_near(box, [&](uint32_t i) {
            if (i < first && point_in_ring(p, *surface_->polygon(i).outer)) first = i;
        });
        return first == UINT32_MAX ? nullptr : surface_->polygon(first).outer;
    }
    bool blocked(Vec2 p) const { return surface_containing(p) || buildings_->contains(p); }
    double ground_z(Vec2 p) const { return sidewalks_->contains(p) ? scene_.sidewalks.front().curb_height : 0.0; }

private:
    const Scene& scene_;
    std::optional<BuildingIndex> buildings_, surface_, sidewalks_;  // road quads and joints, sidewalks
};

// The map's own lamps, moved off the carriageway when they stand on it.
std::vector<Lamp> place_tagged_lamps(const OsmData& osm, const Projection& projection,
                                     const LampObstacles& obstacles, const LampParams& params,
                                     PointGrid& tagged, ParseReport& report) {
    std::vector<Lamp> lamps;
    for (const OsmNode& node : osm.street_lamps) {
        Vec2 p = projection.to_local(node.location.lat, node.location.lon);
        if (!point_within_limit(p)) {
            report.dropped(ReportKind::TaggedStreetLamps, ReportReason::FarFromOrigin);
            continue;
        }
        if (const Ring* ring = obstacles.surface_containing(p)) {
            p = push_out_of(*ring, p, kKerbOffset);
            report.note(ReportKind::TaggedStreetLamps, ReportReason::MovedOffRoad);
        }
        if (obstacles.blocked(p)) {
            report.dropped(ReportKind::TaggedStreetLamps, ReportReason::InsideRoadOrBuilding);
            continue;
        }
        Lamp lamp;
        lamp.osm = {OsmType::Node, node.id};
        lamp.height = params.height;
        if (std::optional<double> h = parse_osm_length(node.tags.get("height"));
            h && *h >= kMinTaggedHeight && *h <= kMaxTaggedHeight)
            lamp.height = *h;
        lamp.position = {p.x, p.y, obstacles.ground_z(p)};
        lamp.source = LampSource::Tagged;
        lamps.push_back(lamp);
        tagged.add(p);
    }
    report.kept(ReportKind::TaggedStreetLamps, static_cast<int64_t>(lamps.size()));
    return lamps;
}

// Candidate spots along one road: `count` of them, each first on one side, then on the other.
struct Spot {
    Vec2 first;
    bool first_blocked = true;
    double first_z = 0;
};
struct RoadSpots {
    Vec2 from, d, n;
    double t0 = 0, offset = 0, phase = 0, spacing = 0;
    uint64_t h = 0;
    std::vector<Spot> spots;

    Vec2 side_point(int k, bool left) const {
        const double t = t0 + (k + 1 - phase) * spacing;
        return from + d * t + n * (left ? offset : -offset);
    }
    bool left_first(int k) const { return ((k + (h >> 60)) & 1) == 0; }
};

// The spots of one road and, for the first side of each, whether it is blocked and its ground
// height: none of this depends on the lamps placed before it.
RoadSpots road_spots(const RoadEdge& road, const LampObstacles& obstacles, const LampParams& params, uint64_t seed) {
    RoadSpots r;
    r.spacing = params.spacing;
    r.from = road.centreline.front();
    const Vec2 to = road.centreline.back();
    r.d = normalize(to - r.from);
    r.n = perp_left(r.d);
    // Usable stretch: the quad's extent along the centreline.
    r.t0 = std::max(dot(road.quad[0] - r.from, r.d), dot(road.quad[3] - r.from, r.d));
    const double t1 = std::min(dot(road.quad[1] - r.from, r.d), dot(road.quad[2] - r.from, r.d));
    if (t1 <= r.t0) return r;
    // A random phase per edge keeps the average at one lamp per `spacing` even on edges
    // shorter than it.
    r.h = hash_keys(seed, static_cast<uint64_t>(road.osm.id), static_cast<uint64_t>(road.from_node),
                    static_cast<uint64_t>(road.to_node));
    r.phase = hash_to_unit(r.h);
    r.offset = 0.5 * road.width + kKerbOffset;
    const int count = static_cast<int>(std::floor((t1 - r.t0) / params.spacing + r.phase));
    r.spots.reserve(static_cast<size_t>(std::max(count, 0)));  // exactly: not grown by doubling
    for (int k = 0; k < count; ++k) {
        Spot s;
        s.first = r.side_point(k, r.left_first(k));
        s.first_blocked = obstacles.blocked(s.first);
        if (!s.first_blocked) s.first_z = obstacles.ground_z(s.first);
        r.spots.push_back(s);
    }
    return r;
}

// Lamps along every road at `params.spacing`, away from the map's own and from each other.
// The spots are found in parallel; only the distance to lamps already placed is decided in
// order, as one loop over the roads would.
int64_t place_generated_lamps(const Scene& scene, const LampObstacles& obstacles, const LampParams& params,
                              uint64_t seed, const PointGrid& tagged, std::vector<Lamp>& lamps) {
    PointGrid generated(std::max(0.5 * params.spacing, 1.0));
    int64_t placed = 0;
    auto too_close = [&](Vec2 p) {
        return tagged.any_within(p, params.min_distance_to_tagged) || generated.any_within(p, 0.5 * params.spacing);
    };
    // The roads are taken a batch at a time, so the spots of every road are not held at once:
    // the same lamps in the same order, as each batch is decided in order.
    constexpr size_t kRoadsPerBatch = 1024;
    std::vector<RoadSpots> roads;
    for (size_t begin = 0; begin < scene.roads.size(); begin += kRoadsPerBatch) {
        const size_t end = std::min(scene.roads.size(), begin + kRoadsPerBatch);
        roads.assign(end - begin, RoadSpots{});
        tbb::parallel_for(tbb::blocked_range<size_t>(begin, end, 64), [&](const tbb::blocked_range<size_t>& range) {
            for (size_t i = range.begin(); i != range.end(); ++i)
                roads[i - begin] = road_spots(scene.roads[i], obstacles, params, seed);
        });
        for (size_t i = begin; i < end; ++i) {
            const RoadSpots& r = roads[i - begin];
            for (int k = 0; k < static_cast<int>(r.spots.size()); ++k) {
                const Spot& s = r.spots[static_cast<size_t>(k)];
                Vec2 p = s.first;
                double z = s.first_z;
                if (s.first_blocked || too_close(p)) {
                    p = r.side_point(k, !r.left_first(k));
                    if (obstacles.blocked(p) || too_close(p)) continue;
                    z = obstacles.ground_z(p);
                }
                Lamp lamp;
                lamp.osm = scene.roads[i].osm;
                lamp.position = {p.x, p.y, z};
                lamp.height = params.height;
                lamp.source = LampSource::Generated;
                lamps.push_back(lamp);
                generated.add(p);
                ++placed;
            }
        }
    }
    return placed;
}

}  // namespace

std::vector<Lamp> place_lamps(const OsmData& osm, const Projection& projection, const Scene& scene,
                              const LampParams& params, uint64_t seed, ParseReport& report) {
    const LampObstacles obstacles(scene);
    PointGrid tagged(std::max(params.min_distance_to_tagged, 1.0));
    std::vector<Lamp> lamps = place_tagged_lamps(osm, projection, obstacles, params, tagged, report);
    report.kept(ReportKind::GeneratedStreetLamps, place_generated_lamps(scene, obstacles, params, seed, tagged, lamps));
    return lamps;
}

}  // namespace citygen
