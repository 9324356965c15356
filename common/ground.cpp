#include "common/ground.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "common/grid_nodes.h"

namespace citygen {

double field_surface_height(const HeightField& field, double x, double y) {
    if (field.empty() || field.nx < 2 || field.ny < 2) return 0;
    const double u = std::clamp((x - field.origin.x) / field.cell, 0.0, field.nx - 1.0);
    const double v = std::clamp((y - field.origin.y) / field.cell, 0.0, field.ny - 1.0);
    const uint32_t i = std::min(static_cast<uint32_t>(u), field.nx - 2);
    const uint32_t j = std::min(static_cast<uint32_t>(v), field.ny - 2);
    const double fu = u - i, fv = v - j;
    const size_t k = static_cast<size_t>(j) * field.nx + i;
    const double h00 = field.heights[k], h10 = field.heights[k + 1];
    const double h01 = field.heights[k + field.nx], h11 = field.heights[k + field.nx + 1];
    // South-east triangle (00, 10, 11) where fu >= fv, north-west (00, 11, 01) otherwise.
    if (fu >= fv) return h00 + fu * (h10 - h00) + fv * (h11 - h10);
    return h00 + fv * (h01 - h00) + fu * (h11 - h01);
}

double ground_height(const Scene& scene, double x, double y) {
    if (scene.terrain.empty()) return scene.ground.z;
    return field_surface_height(scene.terrain, x, y);
}

// Grid lines are u or v integer, diagonals u - v integer.
std::vector<double> field_line_crossings(const HeightField& f, Vec2 a, Vec2 b) {
    std::vector<double> ts;
    const double ua = (a.x - f.origin.x) / f.cell, va = (a.y - f.origin.y) / f.cell;
    const double du = (b.x - a.x) / f.cell, dv = (b.y - a.y) / f.cell;
    auto crossings = [&](double start, double delta) {
        if (std::abs(delta) < 1e-12) return;
        const double end = start + delta;
        for (double k = std::ceil(std::min(start, end)); k <= std::max(start, end); k += 1) {
            const double t = (k - start) / delta;
            if (t > 1e-9 && t < 1 - 1e-9) ts.push_back(t);
        }
    };
    crossings(ua, du);
    crossings(va, dv);
    crossings(ua - va, du - dv);
    std::sort(ts.begin(), ts.end());
    return ts;
}

namespace {

double lowest_along_edge(const HeightField& f, Vec2 a, Vec2 b) {
    double lowest = std::min(field_surface_height(f, a.x, a.y), field_surface_height(f, b.x, b.y));
    for (double t : field_line_crossings(f, a, b)) {
        const Vec2 p = a + (b - a) * t;
        lowest = std::min(lowest, field_surface_height(f, p.x, p.y));
    }
    return lowest;
}

}  // namespace

namespace {

std::vector<const Ring*> rings_of(const LandCover& c) {
    std::vector<const Ring*> rings{&c.outer};
    for (const Ring& hole : c.holes) rings.push_back(&hole);
    return rings;
}

}  // namespace

std::vector<uint8_t> sea_nodes(const HeightField& field, const std::vector<LandCover>& land_cover) {
    std::vector<uint8_t> sea;
    if (field.empty()) return sea;
    const GridLayout g{field.origin, field.cell, field.nx, field.ny};
    for (const LandCover& c : land_cover) {
        if (c.cover != LandCoverClass::Sea || c.outer.size() < 3) continue;
        if (sea.empty()) sea.assign(field.heights.size(), 0);
        for_each_node_inside(g, rings_of(c), [&](uint32_t i, uint32_t j) { sea[g.index(i, j)] = 1; });
    }
    return sea;
}

std::vector<uint8_t> pier_nodes(const HeightField& field, const std::vector<LandCover>& land_cover) {
    const std::vector<uint8_t> sea = sea_nodes(field, land_cover);
    if (sea.empty()) return {};
    std::vector<uint8_t> pier(sea.size(), 0);
    const GridLayout g{field.origin, field.cell, field.nx, field.ny};
    const double margin = field.cell * std::sqrt(2.0);
    const auto mark = [&](uint32_t i, uint32_t j) { pier[g.index(i, j)] = sea[g.index(i, j)]; };
    for (const LandCover& c : land_cover) {
        if (c.cover != LandCoverClass::Paved || c.outer.size() < 3) continue;
        const std::vector<const Ring*> rings = rings_of(c);
        for_each_node_inside(g, rings, mark);
        for (const Ring* ring : rings)
            for (size_t a = 0; a < ring->size(); ++a)
                for_each_node_near(g, (*ring)[a], (*ring)[(a + 1) % ring->size()], margin,
                                   [&](uint32_t i, uint32_t j, double, double) { mark(i, j); });
    }
    return pier;
}

double building_base(const Scene& scene, const Building& building) {
    if (scene.terrain.empty() || building.outer.empty()) return scene.ground.z;
    const HeightField& f = scene.terrain;
    double lowest = ground_height(scene, building.outer[0].x, building.outer[0].y);
    for (size_t k = 0, n = building.outer.size(); k < n; ++k)
        lowest = std::min(lowest, lowest_along_edge(f, building.outer[k], building.outer[(k + 1) % n]));
    // Nodes inside the footprint (a large footprint may hold a dip no edge touches).
    const Box2 box = bounds_of(building.outer);
    const long i0 = std::max(0L, static_cast<long>(std::ceil((box.min.x - f.origin.x) / f.cell)));
    const long j0 = std::max(0L, static_cast<long>(std::ceil((box.min.y - f.origin.y) / f.cell)));
    const long i1 = std::min<long>(f.nx - 1, static_cast<long>(std::floor((box.max.x - f.origin.x) / f.cell)));
    const long j1 = std::min<long>(f.ny - 1, static_cast<long>(std::floor((box.max.y - f.origin.y) / f.cell)));
    for (long j = j0; j <= j1; ++j)
        for (long i = i0; i <= i1; ++i) {
            const Vec3 p = field_node(f, static_cast<uint32_t>(i), static_cast<uint32_t>(j));
            if (point_in_ring({p.x, p.y}, building.outer)) lowest = std::min(lowest, p.z);
        }
    return lowest;
}

}  // namespace citygen
