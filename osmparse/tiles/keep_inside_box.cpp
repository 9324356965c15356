#include "osmparse/tiles/keep_inside_box.h"

#include <algorithm>
#include <cmath>

#include "osmparse/map/assemble_sea.h"

namespace citygen {

namespace {

// Which objects of a list stay, and the new index of each (-1: dropped).
struct Kept {
    std::vector<int> index;
    int count = 0;
    bool has(int i) const { return i >= 0 && static_cast<size_t>(i) < index.size() && index[i] >= 0; }
    int renumbered(int i) const { return has(i) ? index[i] : -1; }
};

template <typename T, typename Inside>
Kept choose(const std::vector<T>& items, Inside inside) {
    Kept k;
    k.index.assign(items.size(), -1);
    for (size_t i = 0; i < items.size(); ++i)
        if (inside(items[i])) k.index[i] = k.count++;
    return k;
}

// Moves the kept objects to the front, in their order, and drops the rest.
template <typename T>
void compact(std::vector<T>& items, const Kept& k) {
    for (size_t i = 0; i < items.size(); ++i)
        if (k.index[i] >= 0 && static_cast<size_t>(k.index[i]) != i) items[k.index[i]] = std::move(items[i]);
    items.resize(static_cast<size_t>(k.count));
}

void renumber_edges(std::vector<uint32_t>& edges, const Kept& k) {
    std::vector<uint32_t> out;
    for (uint32_t e : edges)
        if (k.has(static_cast<int>(e))) out.push_back(static_cast<uint32_t>(k.index[e]));
    edges = std::move(out);
}

void count(ParseReport& report, ReportKind kind, const Kept& k) {
    const auto total = static_cast<int64_t>(k.index.size());
    report.read(kind, total);
    report.kept(kind, k.count);
    if (total > k.count) report.dropped(kind, ReportReason::AnchorInAnotherTile, total - k.count);
}

// The decisions for every list of the scene, before anything is renumbered.
struct TileChoice {
    Kept buildings, roads, joints, sidewalks, lamps, land_cover, trees, paths, path_joints, crossings, walls;
};

template <typename Inside>
TileChoice choose_all(const Scene& s, Inside inside) {
    TileChoice c;
    auto ring_inside = [&](const Ring& r) { return inside(ring_anchor(r)); };
    c.buildings = choose(s.buildings, [&](const Building& b) { return ring_inside(b.outer); });
    c.roads = choose(s.roads, [&](const RoadEdge& r) { return inside(edge_anchor(r.centreline)); });
    c.joints = choose(s.joints, [&](const Joint& j) {
        return j.edges.empty() ? ring_inside(j.polygon) : c.roads.has(static_cast<int>(j.edges.front()));
    });
    c.sidewalks = choose(s.sidewalks, [&](const Sidewalk& w) {
        if (w.joint >= 0 && (w.kind == SidewalkKind::Corner || w.road < 0)) return c.joints.has(w.joint);
        return w.road >= 0 ? c.roads.has(w.road) : ring_inside(w.polygon);
    });
    c.lamps = choose(s.lamps, [&](const Lamp& l) { return inside({l.position.x, l.position.y}); });
    c.land_cover = choose(s.land_cover, [&](const LandCover& l) { return l.cover == LandCoverClass::Sea || ring_inside(l.outer); });
    c.trees = choose(s.trees, [&](const Tree& t) { return inside(t.position); });
    c.paths = choose(s.paths, [&](const PathEdge& p) { return inside(edge_anchor(p.centreline)); });
    c.path_joints = choose(s.path_joints, [&](const Joint& j) {
        return j.edges.empty() ? ring_inside(j.polygon) : c.paths.has(static_cast<int>(j.edges.front()));
    });
    c.crossings =
        choose(s.crossings, [&](const Crossing& x) { return x.road >= 0 ? c.roads.has(x.road) : inside(x.position); });
    c.walls = choose(s.retaining_walls, [&](const RetainingWall& w) { return inside(edge_anchor(w.line)); });
    return c;
}

void renumber_references(Scene& s, const TileChoice& c) {
    for (RoadEdge& r : s.roads) {
        r.from_joint = c.joints.renumbered(r.from_joint);
        r.to_joint = c.joints.renumbered(r.to_joint);
    }
    for (Joint& j : s.joints) renumber_edges(j.edges, c.roads);
    for (Sidewalk& w : s.sidewalks) {
        w.road = c.roads.renumbered(w.road);
        w.joint = c.joints.renumbered(w.joint);
    }
    for (PathEdge& p : s.paths) {
        p.from_joint = c.path_joints.renumbered(p.from_joint);
        p.to_joint = c.path_joints.renumbered(p.to_joint);
    }
    for (Joint& j : s.path_joints) renumber_edges(j.edges, c.paths);
    for (Crossing& x : s.crossings) x.road = c.roads.renumbered(x.road);
}

}  // namespace

Vec2 ring_anchor(const Ring& ring) {
    if (ring.empty()) return {0, 0};
    // Relative to the first point, so far from the origin the products keep their digits.
    const Vec2 o = ring.front();
    double a = 0, cx = 0, cy = 0;
    for (size_t i = 0, n = ring.size(); i < n; ++i) {
        const Vec2 p = ring[i] - o, q = ring[(i + 1) % n] - o;
        const double w = cross(p, q);
        a += w;
        cx += (p.x + q.x) * w;
        cy += (p.y + q.y) * w;
    }
    const Box2 box = bounds_of(ring);
    const double size = std::max(box.max.x - box.min.x, box.max.y - box.min.y);
    if (!(std::fabs(a) > 1e-9 * size * size)) return (box.min + box.max) * 0.5;
    return o + Vec2(cx / (3 * a), cy / (3 * a));
}

Vec2 edge_anchor(const std::vector<Vec2>& centreline) {
    if (centreline.empty()) return {0, 0};
    return (centreline.front() + centreline.back()) * 0.5;
}

Box2 tile_sea_box(const LatLonBox& core, const OsmData& osm, const Projection& projection) {
    const auto [lo, hi] = extract_bounds(osm);
    const LatLon min{std::max(core.min.lat, lo.lat), std::max(core.min.lon, lo.lon)};
    const LatLon max{std::min(core.max.lat, hi.lat), std::min(core.max.lon, hi.lon)};
    Box2 box;
    if (min.lat >= max.lat || min.lon >= max.lon) return box;
    constexpr int kSamples = 64;  // per edge: a tile's edge bends by metres, not more, between them
    for (int i = 0; i <= kSamples; ++i) {
        const double t = static_cast<double>(i) / kSamples;
        const double lat = min.lat + t * (max.lat - min.lat), lon = min.lon + t * (max.lon - min.lon);
        for (const LatLon p : {LatLon{lat, min.lon}, LatLon{lat, max.lon}, LatLon{min.lat, lon}, LatLon{max.lat, lon}})
            box.extend(projection.to_local(p.lat, p.lon));
    }
    const Box2 extract = extract_box(osm, projection);
    box.min = Vec2(std::max(box.min.x - 1, extract.min.x), std::max(box.min.y - 1, extract.min.y));
    box.max = Vec2(std::min(box.max.x + 1, extract.max.x), std::min(box.max.y + 1, extract.max.y));
    return box;
}

bool box_holds(const LatLonBox& box, const Projection& projection, Vec2 point) {
    LatLon l;
    projection.to_wgs84(point, l.lat, l.lon);
    return box.contains(l);
}

size_t keep_inside_box(Scene& scene, const Projection& projection, const LatLonBox& box, ParseReport& report,
                       size_t leading) {
    auto inside = [&](Vec2 p) { return box_holds(box, projection, p); };
    const TileChoice c = choose_all(scene, inside);
    const size_t leading_kept = static_cast<size_t>(std::count_if(
        c.buildings.index.begin(), c.buildings.index.begin() + std::min(leading, c.buildings.index.size()),
        [](int i) { return i >= 0; }));
    renumber_references(scene, c);
    compact(scene.buildings, c.buildings);
    compact(scene.roads, c.roads);
    compact(scene.joints, c.joints);
    compact(scene.sidewalks, c.sidewalks);
    compact(scene.lamps, c.lamps);
    compact(scene.land_cover, c.land_cover);
    compact(scene.trees, c.trees);
    compact(scene.paths, c.paths);
    compact(scene.path_joints, c.path_joints);
    compact(scene.crossings, c.crossings);
    compact(scene.retaining_walls, c.walls);
    using K = ReportKind;
    count(report, K::TileBuildings, c.buildings);
    count(report, K::TileRoadEdges, c.roads);
    count(report, K::TileRoadJoints, c.joints);
    count(report, K::TileSidewalks, c.sidewalks);
    count(report, K::TilePathEdges, c.paths);
    count(report, K::TilePathJoints, c.path_joints);
    count(report, K::TileCrossings, c.crossings);
    count(report, K::TileLamps, c.lamps);
    count(report, K::TileLandCover, c.land_cover);
    count(report, K::TileTrees, c.trees);
    // Walls come only with --dem: without them the report is what it was.
    if (!c.walls.index.empty()) count(report, K::TileRetainingWalls, c.walls);
    return leading_kept;
}

}  // namespace citygen
