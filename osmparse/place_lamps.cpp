#include "place_lamps.h"

#include <algorithm>
#include <cmath>

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
    const BuildingIndex buildings(scene.buildings);
    std::vector<Building> surface_pieces;  // road quads and joints, indexed like footprints
    for (const RoadEdge& r : scene.roads) surface_pieces.push_back({r.osm, r.quad, {}, 0, 0, 0, {}, {}, false});
    for (const Joint& j : scene.joints) surface_pieces.push_back({j.osm, j.polygon, {}, 0, 0, 0, {}, {}, false});
    const BuildingIndex surface(surface_pieces);
    std::vector<Building> walk_pieces;
    for (const Sidewalk& s : scene.sidewalks) walk_pieces.push_back({{}, s.polygon, {}, 0, 0, 0, {}, {}, false});
    const BuildingIndex sidewalks(walk_pieces);

    auto surface_containing = [&](Vec2 p) -> const Ring* {
        Box2 box;
        box.extend(p);
        for (uint32_t i : surface.near(box))
            if (point_in_ring(p, surface_pieces[i].outer)) return &surface_pieces[i].outer;
        return nullptr;
    };
    auto ground_z = [&](Vec2 p) { return sidewalks.contains(p) ? scene.sidewalks.front().curb_height : 0.0; };

    std::vector<Lamp> lamps;
    PointGrid tagged(std::max(params.min_distance_to_tagged, 1.0));
    for (const OsmNode& node : osm.street_lamps) {
        Vec2 p = projection.to_local(node.location.lat, node.location.lon);
        if (std::max(std::fabs(p.x), std::fabs(p.y)) > kMaxCoordinate) {
            report.dropped(kTaggedStreetLamps, kTooFarOut);
            continue;
        }
        if (const Ring* ring = surface_containing(p)) {
            p = push_out_of(*ring, p, kKerbOffset);
            report.note(kTaggedStreetLamps, kMovedOffRoad);
        }
        if (surface_containing(p) || buildings.contains(p)) {
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

    PointGrid generated(std::max(0.5 * params.spacing, 1.0));
    int64_t placed = 0;
    for (const RoadEdge& road : scene.roads) {
        const Vec2 from = road.centreline.front(), to = road.centreline.back();
        const Vec2 d = normalize(to - from), n = perp_left(d);
        // Usable stretch: the quad's extent along the centreline.
        const double t0 = std::max(dot(road.quad[0] - from, d), dot(road.quad[3] - from, d));
        const double t1 = std::min(dot(road.quad[1] - from, d), dot(road.quad[2] - from, d));
        if (t1 <= t0) continue;
        // A random phase per edge keeps the average at one lamp per `spacing` even on
        // edges shorter than it.
        const uint64_t h = hash_keys(seed, static_cast<uint64_t>(road.osm.id), static_cast<uint64_t>(road.from_node),
                                     static_cast<uint64_t>(road.to_node));
        const double phase = hash_to_unit(h);
        const int count = static_cast<int>(std::floor((t1 - t0) / params.spacing + phase));
        for (int k = 0; k < count; ++k) {
            const double t = t0 + (k + 1 - phase) * params.spacing;
            const bool left_first = ((k + (h >> 60)) & 1) == 0;
            for (int attempt = 0; attempt < 2; ++attempt) {
                const bool left = left_first != (attempt == 1);
                const double offset = 0.5 * road.width + kKerbOffset;
                const Vec2 p = from + d * t + n * (left ? offset : -offset);
                if (surface_containing(p) || buildings.contains(p) ||
                    tagged.any_within(p, params.min_distance_to_tagged) || generated.any_within(p, 0.5 * params.spacing))
                    continue;
                Lamp lamp;
                lamp.osm = road.osm;
                lamp.position = {p.x, p.y, ground_z(p)};
                lamp.height = params.height;
                lamp.source = LampSource::Generated;
                lamps.push_back(lamp);
                generated.add(p);
                ++placed;
                break;
            }
        }
    }
    report.kept(kGeneratedStreetLamps, placed);
    return lamps;
}

}  // namespace citygen
