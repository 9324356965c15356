#include "render/geometry/ground.h"

#include <algorithm>
#include <array>
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

// Where the segment a->b crosses the field's grid lines (u or v integer) and diagonals (u - v
// integer), as parameters in (0, 1), ascending: the drawn ground is linear between them.
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

double lowest_along_edge(const HeightField& f, Vec2 a, Vec2 b) {
    double lowest = std::min(field_surface_height(f, a.x, a.y), field_surface_height(f, b.x, b.y));
    for (double t : field_line_crossings(f, a, b)) {
        const Vec2 p = a + (b - a) * t;
        lowest = std::min(lowest, field_surface_height(f, p.x, p.y));
    }
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

Ring split_at_field_lines(const Scene& scene, const Ring& ring) {
    if (scene.terrain.empty()) return ring;
    Ring out;
    out.reserve(ring.size());
    for (size_t k = 0, n = ring.size(); k < n; ++k) {
        const Vec2 a = ring[k], b = ring[(k + 1) % n];
        out.push_back(a);
        for (double t : field_line_crossings(scene.terrain, a, b)) out.push_back(a + (b - a) * t);
    }
    return out;
}

namespace {

// The convex polygon `poly` (counter-clockwise) cut to the side of the line through a, b where
// cross(b - a, p - a) >= 0 (Sutherland-Hodgman, one edge).
void clip_to_half_plane(std::vector<Vec2>& poly, Vec2 a, Vec2 b, std::vector<Vec2>& scratch) {
    scratch.clear();
    const Vec2 d = b - a;
    for (size_t k = 0, n = poly.size(); k < n; ++k) {
        const Vec2 p = poly[k], q = poly[(k + 1) % n];
        const double sp = cross(d, p - a), sq = cross(d, q - a);
        if (sp >= 0) scratch.push_back(p);
        if ((sp >= 0) != (sq >= 0)) scratch.push_back(p + (q - p) * (sp / (sp - sq)));
    }
    poly.swap(scratch);
}

// Adds triangle (a, b, c) to `out` cut into its pieces over the field's cell triangles, so that
// each piece lies in one plane of the drawn ground and the draped surface follows it exactly.
// A triangle reaching beyond the grid is draped at its corners only (nothing is drawn there but
// the skirt).
void add_draped_triangle(const Scene& scene, Vec2 a, Vec2 b, Vec2 c, double lift, DrapedPolygon& out) {
    const HeightField& f = scene.terrain;
    auto add_point = [&](Vec2 p) {
        out.points.push_back({p.x, p.y, ground_height(scene, p.x, p.y) + lift});
        return static_cast<uint32_t>(out.points.size() - 1);
    };
    const double u0 = (std::min({a.x, b.x, c.x}) - f.origin.x) / f.cell, u1 = (std::max({a.x, b.x, c.x}) - f.origin.x) / f.cell;
    const double v0 = (std::min({a.y, b.y, c.y}) - f.origin.y) / f.cell, v1 = (std::max({a.y, b.y, c.y}) - f.origin.y) / f.cell;
    if (u0 < 0 || v0 < 0 || u1 > f.nx - 1.0 || v1 > f.ny - 1.0 || cross(b - a, c - a) <= 0) {
        out.triangles.push_back({add_point(a), add_point(b), add_point(c)});
        return;
    }
    std::vector<Vec2> poly, scratch;
    const uint32_t i_end = std::min(f.nx - 2, static_cast<uint32_t>(u1)), j_end = std::min(f.ny - 2, static_cast<uint32_t>(v1));
    for (uint32_t j = static_cast<uint32_t>(v0); j <= j_end; ++j)
        for (uint32_t i = static_cast<uint32_t>(u0); i <= i_end; ++i) {
            const Vec3 n00 = field_node(f, i, j), n11 = field_node(f, i + 1, j + 1);
            const Vec2 p00{n00.x, n00.y}, p10{n11.x, n00.y}, p11{n11.x, n11.y}, p01{n00.x, n11.y};
            // The cell's two triangles, as field_surface_height splits it.
            for (const auto& tri : {std::array<Vec2, 3>{p00, p10, p11}, std::array<Vec2, 3>{p00, p11, p01}}) {
                poly = {a, b, c};
                for (int e = 0; e < 3 && poly.size() >= 3; ++e) clip_to_half_plane(poly, tri[e], tri[(e + 1) % 3], scratch);
                if (poly.size() < 3) continue;
                double area = 0;
                for (size_t k = 1; k + 1 < poly.size(); ++k) area += cross(poly[k] - poly[0], poly[k + 1] - poly[0]);
                if (area <= 1e-9) continue;
                const uint32_t first = add_point(poly[0]);
                uint32_t previous = add_point(poly[1]);
                for (size_t k = 2; k < poly.size(); ++k) {
                    const uint32_t next = add_point(poly[k]);
                    out.triangles.push_back({first, previous, next});
                    previous = next;
                }
            }
        }
}

}  // namespace

DrapedPolygon drape_polygon(const Scene& scene, const Ring& outer, const std::vector<Ring>& holes, double lift) {
    const PolygonTriangulation tri = triangulate_polygon(outer, holes);
    DrapedPolygon out;
    for (const auto& t : tri.triangles)
        add_draped_triangle(scene, tri.points[t[0]], tri.points[t[1]], tri.points[t[2]], lift, out);
    return out;
}

}  // namespace citygen
