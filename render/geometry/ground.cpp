#include "render/geometry/ground.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

namespace citygen {

void sink_field_under_sea(Scene& scene) {
    HeightField& f = scene.terrain;
    const std::vector<uint8_t> sea = sea_nodes(f, scene.land_cover);
    if (sea.empty()) return;
    const std::vector<uint8_t> pier = pier_nodes(f, scene.land_cover);
    for (size_t n = 0; n < sea.size(); ++n)
        if (sea[n] && !pier[n]) f.heights[n] = std::min(f.heights[n], static_cast<float>(kSeaFloor));
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
