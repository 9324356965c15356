#include "render/geometry/land_cover_geometry.h"

#include <algorithm>
#include <cmath>

#include "render/geometry/stored_geometry.h"
#include "render/geometry/surface_detail.h"
#include "render/geometry/triangulate_polygon.h"
#include "render/materials/materials.h"

namespace citygen {

namespace {

constexpr double kLandCoverStep = 0.002;  // metres between class layers
constexpr size_t kTileVertices = 32;      // about this many vertices per procedural tile

// The part of `ring` inside the axis-aligned box (Sutherland-Hodgman). The result may run
// along the box edge, but inside the box it winds around every point exactly as `ring` does,
// which is all a point-in-polygon test needs.
Ring clip_ring_to_box(const Ring& ring, const Box2& box) {
    Ring out = ring;
    for (int side = 0; side < 4 && !out.empty(); ++side) {
        auto inside = [&](Vec2 p) {
            switch (side) {
                case 0: return p.x >= box.min.x;
                case 1: return p.x <= box.max.x;
                case 2: return p.y >= box.min.y;
                default: return p.y <= box.max.y;
            }
        };
        auto crossing = [&](Vec2 a, Vec2 b) {
            double t;
            switch (side) {
                case 0: t = (box.min.x - a.x) / (b.x - a.x); break;
                case 1: t = (box.max.x - a.x) / (b.x - a.x); break;
                case 2: t = (box.min.y - a.y) / (b.y - a.y); break;
                default: t = (box.max.y - a.y) / (b.y - a.y); break;
            }
            Vec2 p = a + (b - a) * t;
            if (side == 0) p.x = box.min.x;
            if (side == 1) p.x = box.max.x;
            if (side == 2) p.y = box.min.y;
            if (side == 3) p.y = box.max.y;
            return p;
        };
        Ring in = std::move(out);
        out.clear();
        for (size_t i = 0, n = in.size(); i < n; ++i) {
            const Vec2 a = in[i], b = in[(i + 1) % n];
            const bool ia = inside(a), ib = inside(b);
            if (ia) out.push_back(a);
            if (ia != ib) out.push_back(crossing(a, b));
        }
    }
    return std::fabs(signed_area(out)) > 1e-9 ? out : Ring{};
}

size_t vertex_count(const LandCover& c) {
    size_t n = c.outer.size();
    for (const Ring& h : c.holes) n += h.size();
    return n;
}

// A smooth pseudo-random value per integer lattice point.
double lattice(int64_t x, int64_t y, uint32_t seed) {
    uint64_t h = static_cast<uint64_t>(x) * 0x9E3779B97F4A7C15ull ^ static_cast<uint64_t>(y) * 0xC2B2AE3D27D4EB4Full ^ seed;
    h ^= h >> 33;
    h *= 0xff51afd7ed558ccdull;
    h ^= h >> 33;
    return static_cast<double>(h >> 11) * 0x1.0p-53;
}

void add_flat_polygon_with_holes(const LandCover& c, double z, uint32_t object, TriangleMesh& mesh) {
    const PolygonTriangulation tri = triangulate_polygon(c.outer, c.holes);
    const uint32_t first = static_cast<uint32_t>(mesh.vertex_count());
    for (Vec2 p : tri.points) mesh.add_vertex({p.x, p.y, z});
    for (const auto& t : tri.triangles)
        mesh.add_triangle(first + t[0], first + t[1], first + t[2], object, land_cover_material(c.cover));
}

}  // namespace

double land_cover_lift(LandCoverClass c) { return kLandCoverStep * (1 + land_cover_priority(c)); }

double land_cover_z(const Scene& scene, LandCoverClass c) { return scene.ground.z + land_cover_lift(c); }

uint16_t land_cover_material(LandCoverClass c) {
    switch (c) {
        case LandCoverClass::Water: return kWater;
        case LandCoverClass::Sea: return kSea;
        case LandCoverClass::Green: return kGrass;
        case LandCoverClass::Forest: return kForestFloor;
        case LandCoverClass::Paved: return kPaving;
        case LandCoverClass::Sand: return kSand;
        case LandCoverClass::Farmland: return kFarmland;
        case LandCoverClass::BuiltUp: return kUrbanGround;
    }
    return kGround;
}

TriangleMesh build_stored_land_cover(const Scene& scene) {
    TriangleMesh mesh;
    mesh.kind = ObjectKind::LandCover;
    for (uint32_t i = 0; i < scene.land_cover.size(); ++i) {
        const LandCover& c = scene.land_cover[i];
        if (c.outer.size() < 3) continue;
        if (c.cover == LandCoverClass::Sea) {  // at sea level, on a field too
            add_flat_polygon_with_holes(c, land_cover_z(scene, c.cover), i, mesh);
            continue;
        }
        add_ground_polygon(scene, c.outer, c.holes, land_cover_lift(c.cover), i, land_cover_material(c.cover), mesh);
    }
    return mesh;
}

std::unique_ptr<ProceduralGeometry> build_procedural_land_cover(const Scene& scene) {
    ProceduralGeometry::SurfaceMaterials walls;
    walls.fill(kGround);
    auto geometry = std::make_unique<ProceduralGeometry>(ObjectKind::LandCover, walls);
    for (uint32_t i = 0; i < scene.land_cover.size(); ++i) {
        const LandCover& c = scene.land_cover[i];
        if (c.outer.size() < 3) continue;
        const double z = land_cover_z(scene, c.cover);
        const uint16_t material = land_cover_material(c.cover);
        if (!scene.terrain.empty() && c.cover != LandCoverClass::Sea) {
            add_ground_polygon(scene, c.outer, c.holes, land_cover_lift(c.cover), i, material, *geometry);
            continue;
        }
        const size_t n = vertex_count(c);
        if (n <= kTileVertices) {
            geometry->add_polygon(i, c.outer, c.holes, z, material);
            continue;
        }
        const Box2 box = bounds_of(c.outer);
        const int cells = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n) / kTileVertices * 4)));
        const double cw = (box.max.x - box.min.x) / cells, ch = (box.max.y - box.min.y) / cells;
        for (int gx = 0; gx < cells; ++gx)
            for (int gy = 0; gy < cells; ++gy) {
                Box2 tile;
                tile.extend({box.min.x + gx * cw, box.min.y + gy * ch});
                tile.extend({gx + 1 == cells ? box.max.x : box.min.x + (gx + 1) * cw,
                             gy + 1 == cells ? box.max.y : box.min.y + (gy + 1) * ch});
                Ring outer = clip_ring_to_box(c.outer, tile);
                if (outer.empty()) continue;
                std::vector<Ring> holes;
                for (const Ring& h : c.holes) {
                    Ring clipped = clip_ring_to_box(h, tile);
                    if (!clipped.empty()) holes.push_back(std::move(clipped));
                }
                geometry->add_polygon(i, outer, holes, z, material);
            }
    }
    return geometry;
}

Vec3 water_normal(Vec2 p, bool sea) {
    // Wave trains: direction, wavelength (m), slope amplitude. Sum of their gradients, plus
    // value noise at 1.5 m for the ripples that break up reflections.
    struct Train {
        double dx, dy, wavelength, slope;
    };
    static const Train trains[] = {{0.8, 0.6, 7.3, 0.05}, {0.3, -0.95, 4.1, 0.035}, {-0.7, 0.7, 2.3, 0.025},
                                   {0.99, 0.1, 1.3, 0.015}};
    const double scale = sea ? 0.6 : 0.3;
    double gx = 0, gy = 0;
    for (const Train& t : trains) {
        const double k = 2 * kPi / t.wavelength;
        const double phase = k * (t.dx * p.x + t.dy * p.y);
        const double d = t.slope * std::cos(phase + 1.7 * std::sin(0.31 * phase));
        gx += d * t.dx;
        gy += d * t.dy;
    }
    // Ripples: gradient of bilinear value noise.
    const double rx = p.x / 0.9, ry = p.y / 0.9;
    const int64_t ix = static_cast<int64_t>(std::floor(rx)), iy = static_cast<int64_t>(std::floor(ry));
    const double fx = rx - ix, fy = ry - iy;
    const double a = lattice(ix, iy, 7), b = lattice(ix + 1, iy, 7), c = lattice(ix, iy + 1, 7),
                 d = lattice(ix + 1, iy + 1, 7);
    const double ripple = 0.03;
    gx += ripple * ((b - a) * (1 - fy) + (d - c) * fy);
    gy += ripple * ((c - a) * (1 - fx) + (d - b) * fx);
    return normalize(Vec3{-gx * scale, -gy * scale, 1});
}

std::unique_ptr<RenderGeometry> with_water_waves(std::unique_ptr<RenderGeometry> geometry) {
    return std::make_unique<SurfaceDetailGeometry>(std::move(geometry), [](Hit& hit) {
        if (hit.material != kWater && hit.material != kSea) return;
        if (hit.geometric_normal.z <= 0) return;
        hit.shading_normal = water_normal({hit.position.x, hit.position.y}, hit.material == kSea);
    });
}

}  // namespace citygen
