#include "render/geometry/ground.h"

#include <algorithm>
#include <cmath>
#include <vector>

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

namespace {

// The lowest ground along the edge a->b: the surface is linear between the points where the
// edge crosses a grid line (u or v integer) or a diagonal (u - v integer).
double lowest_along_edge(const HeightField& f, Vec2 a, Vec2 b) {
    double lowest = std::min(field_surface_height(f, a.x, a.y), field_surface_height(f, b.x, b.y));
    const double ua = (a.x - f.origin.x) / f.cell, va = (a.y - f.origin.y) / f.cell;
    const double du = (b.x - a.x) / f.cell, dv = (b.y - a.y) / f.cell;
    auto crossings = [&](double start, double delta) {
        if (std::abs(delta) < 1e-12) return;
        const double end = start + delta;
        for (double k = std::ceil(std::min(start, end)); k <= std::max(start, end); k += 1) {
            const double t = (k - start) / delta;
            lowest = std::min(lowest, field_surface_height(f, a.x + t * (b.x - a.x), a.y + t * (b.y - a.y)));
        }
    };
    crossings(ua, du);
    crossings(va, dv);
    crossings(ua - va, du - dv);
    return lowest;
}

}  // namespace

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

namespace {

// The x of every crossing of the rings' edges with the line y, sorted: between pairs lies the inside.
void row_crossings(const LandCover& c, double y, std::vector<double>& xs) {
    xs.clear();
    auto add = [&](const Ring& ring) {
        for (size_t k = 0, n = ring.size(); k < n; ++k) {
            const Vec2 a = ring[k], b = ring[(k + 1) % n];
            if ((a.y <= y) == (b.y <= y)) continue;
            xs.push_back(a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x));
        }
    };
    add(c.outer);
    for (const Ring& h : c.holes) add(h);
    std::sort(xs.begin(), xs.end());
}

}  // namespace

void sink_field_under_sea(Scene& scene) {
    HeightField& f = scene.terrain;
    if (f.empty()) return;
    std::vector<double> xs;
    for (const LandCover& c : scene.land_cover) {
        if (c.cover != LandCoverClass::Sea || c.outer.size() < 3) continue;
        // Scanlines along the node rows: each row's inside spans, nodes within them lowered.
        for (uint32_t j = 0; j < f.ny; ++j) {
            row_crossings(c, f.origin.y + j * f.cell, xs);
            for (size_t k = 0; k + 1 < xs.size(); k += 2) {
                const double u0 = std::ceil((xs[k] - f.origin.x) / f.cell), u1 = std::floor((xs[k + 1] - f.origin.x) / f.cell);
                for (double u = std::max(0.0, u0); u <= std::min(f.nx - 1.0, u1); ++u) {
                    float& h = f.heights[static_cast<size_t>(j) * f.nx + static_cast<uint32_t>(u)];
                    h = std::min(h, static_cast<float>(kSeaFloor));
                }
            }
        }
    }
}

Ring subdivided_for_ground(const Scene& scene, const Ring& ring) {
    if (scene.terrain.empty()) return ring;
    const double step = scene.terrain.cell;
    Ring out;
    out.reserve(ring.size());
    for (size_t k = 0, n = ring.size(); k < n; ++k) {
        const Vec2 a = ring[k], b = ring[(k + 1) % n];
        out.push_back(a);
        const int pieces = static_cast<int>(std::ceil(length(b - a) / step));
        for (int s = 1; s < pieces; ++s) out.push_back(a + (b - a) * (static_cast<double>(s) / pieces));
    }
    return out;
}

DrapedPolygon drape_polygon(const Scene& scene, const Ring& outer, const std::vector<Ring>& holes, double lift) {
    std::vector<Ring> cut_holes;
    for (const Ring& h : holes) cut_holes.push_back(subdivided_for_ground(scene, h));
    const PolygonTriangulation tri = triangulate_polygon(subdivided_for_ground(scene, outer), cut_holes);
    DrapedPolygon out;
    out.points.reserve(tri.points.size());
    for (Vec2 p : tri.points) out.points.push_back({p.x, p.y, ground_height(scene, p.x, p.y) + lift});
    out.triangles = tri.triangles;
    return out;
}

}  // namespace citygen
