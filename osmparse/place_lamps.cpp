#include "place_lamps.h"

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <optional>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_invoke.h>

#include "build_buildings.h"
#include "osm_units.h"
#include "point_placement.h"
#include "polygon_overlap.h"
#include "read_osm.h"
#include "rng.h"
#include "scene_limits.h"

namespace citygen {

namespace {

constexpr double kKerbOffset = 0.5;  // metres beyond the carriageway edge
constexpr double kMinTaggedHeight = 2, kMaxTaggedHeight = 30;

}  // namespace

std::vector<Lamp> place_lamps(const OsmData& osm, const Projection& projection, const Scene& scene,
                              const LampParams& params, uint64_t seed, ParseReport& report) {
    std::optional<BuildingIndex> buildings, surface, sidewalks;  // road quads and joints, sidewalks
    tbb::parallel_invoke([&] { buildings.emplace(scene.buildings); },
                         [&] { surface.emplace(surface_polygons(scene.roads, scene.joints)); },
                         [&] {
                             std::vector<PolygonRef> walk_pieces;
                             walk_pieces.reserve(scene.sidewalks.size());
                             for (const Sidewalk& s : scene.sidewalks) walk_pieces.push_back({&s.polygon});
                             sidewalks.emplace(std::move(walk_pieces));
                         });

    // The first surface piece (in index order) containing p.
    auto surface_containing = [&](Vec2 p) -> const Ring* {
        Box2 box;
        box.extend(p);
        uint32_t first = UINT32_MAX;
        surface->for_each_near(box, [&](uint32_t i) {
            if (i < first && point_in_ring(p, *surface->polygon(i).outer)) first = i;
        });
        return first == UINT32_MAX ? nullptr : surface->polygon(first).outer;
    };
    auto blocked = [&](Vec2 p) { return surface_containing(p) || buildings->contains(p); };
    auto ground_z = [&](Vec2 p) { return sidewalks->contains(p) ? scene.sidewalks.front().curb_height : 0.0; };

    std::vector<Lamp> lamps;
    PointGrid tagged(std::max(params.min_distance_to_tagged, 1.0));
    for (const OsmNode& node : osm.street_lamps) {
        Vec2 p = projection.to_local(node.location.lat, node.location.lon);
        if (!point_within_limit(p)) {
            report.dropped(kTaggedStreetLamps, kTooFarOut);
            continue;
        }
        if (const Ring* ring = surface_containing(p)) {
            p = push_out_of(*ring, p, kKerbOffset);
            report.note(kTaggedStreetLamps, kMovedOffRoad);
        }
        if (blocked(p)) {
            report.dropped(kTaggedStreetLamps, kInsideRoadOrBuilding);
            continue;
        }
        Lamp lamp;
        lamp.osm = {OsmType::Node, node.id};
        lamp.height = params.height;
        if (std::optional<double> h = parse_osm_length(node.tags.get("height"));
            h && *h >= kMinTaggedHeight && *h <= kMaxTaggedHeight)
            lamp.height = *h;
        lamp.position = {p.x, p.y, ground_z(p)};
        lamp.source = LampSource::Tagged;
        lamps.push_back(lamp);
        tagged.add(p);
    }
    report.kept(kTaggedStreetLamps, static_cast<int64_t>(lamps.size()));

    // Candidate spots: per road, `count` of them, each first on one side, then on the other.
    // Whether a spot is inside a road or building, and its ground height, do not depend on the
    // lamps placed before it: they are found for the first side of every spot in parallel. Only
    // the distance to lamps already placed is decided in order, as one loop over the roads would.
    struct Spot {
        Vec2 first;
        bool first_blocked = true;
        double first_z = 0;
    };
    struct RoadSpots {
        Vec2 from, d, n;
        double t0 = 0, offset = 0, phase = 0;
        uint64_t h = 0;
        std::vector<Spot> spots;
    };
    auto side_point = [&](const RoadSpots& r, int k, bool left) {
        const double t = r.t0 + (k + 1 - r.phase) * params.spacing;
        return r.from + r.d * t + r.n * (left ? r.offset : -r.offset);
    };
    auto left_first = [](const RoadSpots& r, int k) { return ((k + (r.h >> 60)) & 1) == 0; };
    PointGrid generated(std::max(0.5 * params.spacing, 1.0));
    int64_t placed = 0;
    auto too_close = [&](Vec2 p) {
        return tagged.any_within(p, params.min_distance_to_tagged) || generated.any_within(p, 0.5 * params.spacing);
    };
    // The roads are taken a batch at a time (the spots of all of them at once were 1.5 MB on
    // Kaiserslautern): the same lamps in the same order, as each batch is decided in order.
    constexpr size_t kRoadsPerBatch = 1024;
    std::vector<RoadSpots> roads;
    for (size_t begin = 0; begin < scene.roads.size(); begin += kRoadsPerBatch) {
        const size_t end = std::min(scene.roads.size(), begin + kRoadsPerBatch);
        roads.assign(end - begin, RoadSpots{});
        tbb::parallel_for(tbb::blocked_range<size_t>(begin, end, 64), [&](const tbb::blocked_range<size_t>& range) {
            for (size_t i = range.begin(); i != range.end(); ++i) {
                const RoadEdge& road = scene.roads[i];
                RoadSpots& r = roads[i - begin];
                r.from = road.centreline.front();
                const Vec2 to = road.centreline.back();
                r.d = normalize(to - r.from);
                r.n = perp_left(r.d);
                // Usable stretch: the quad's extent along the centreline.
                r.t0 = std::max(dot(road.quad[0] - r.from, r.d), dot(road.quad[3] - r.from, r.d));
                const double t1 = std::min(dot(road.quad[1] - r.from, r.d), dot(road.quad[2] - r.from, r.d));
                if (t1 <= r.t0) continue;
                // A random phase per edge keeps the average at one lamp per `spacing` even on
                // edges shorter than it.
                r.h = hash_keys(seed, static_cast<uint64_t>(road.osm.id), static_cast<uint64_t>(road.from_node),
                                static_cast<uint64_t>(road.to_node));
                r.phase = hash_to_unit(r.h);
                r.offset = 0.5 * road.width + kKerbOffset;
                const int count = static_cast<int>(std::floor((t1 - r.t0) / params.spacing + r.phase));
                r.spots.reserve(static_cast<size_t>(std::max(count, 0)));  // exactly: not grown by doubling
                for (int k = 0; k < count; ++k) {
                    Spot s;
                    s.first = side_point(r, k, left_first(r, k));
                    s.first_blocked = blocked(s.first);
                    if (!s.first_blocked) s.first_z = ground_z(s.first);
                    r.spots.push_back(s);
                }
            }
        });
        for (size_t i = begin; i < end; ++i) {
            const RoadSpots& r = roads[i - begin];
            for (int k = 0; k < static_cast<int>(r.spots.size()); ++k) {
                const Spot& s = r.spots[static_cast<size_t>(k)];
                Vec2 p = s.first;
                double z = s.first_z;
                if (s.first_blocked || too_close(p)) {
                    p = side_point(r, k, !left_first(r, k));
                    if (blocked(p) || too_close(p)) continue;
                    z = ground_z(p);
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
    report.kept(kGeneratedStreetLamps, placed);
    return lamps;
}

}  // namespace citygen
