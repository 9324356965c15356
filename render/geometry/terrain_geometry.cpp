#include "render/geometry/terrain_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "render/geometry/ground.h"
#include "render/geometry/stored_geometry.h"
#include "render/materials/materials.h"
#include "render/scene/user_geometry.h"

namespace citygen {

size_t terrain_skirt_count(const HeightField& field) { return 2 * (field.nx - 1) + 2 * (field.ny - 1) + 4; }

// South edges, north edges, west edges, east edges, then the corners SW, SE, NE, NW.
std::array<Vec3, 4> terrain_skirt_quad(const HeightField& f, const Box2& e, size_t k) {
    const uint32_t ni = f.nx - 1, nj = f.ny - 1;
    auto out = [](Vec3 p, double x, double y) { return Vec3{x, y, p.z}; };
    if (k < 2 * size_t{ni}) {
        const uint32_t i = static_cast<uint32_t>(k % ni);
        if (k < ni) {
            const Vec3 s0 = field_node(f, i, 0), s1 = field_node(f, i + 1, 0);
            return {out(s0, s0.x, e.min.y), out(s1, s1.x, e.min.y), s1, s0};
        }
        const Vec3 n0 = field_node(f, i, nj), n1 = field_node(f, i + 1, nj);
        return {n0, n1, out(n1, n1.x, e.max.y), out(n0, n0.x, e.max.y)};
    }
    k -= 2 * size_t{ni};
    if (k < 2 * size_t{nj}) {
        const uint32_t j = static_cast<uint32_t>(k % nj);
        if (k < nj) {
            const Vec3 w0 = field_node(f, 0, j), w1 = field_node(f, 0, j + 1);
            return {out(w0, e.min.x, w0.y), w0, w1, out(w1, e.min.x, w1.y)};
        }
        const Vec3 e0 = field_node(f, ni, j), e1 = field_node(f, ni, j + 1);
        return {e0, out(e0, e.max.x, e0.y), out(e1, e.max.x, e1.y), e1};
    }
    k -= 2 * size_t{nj};
    const Vec3 sw = field_node(f, 0, 0), se = field_node(f, ni, 0), nw = field_node(f, 0, nj), ne = field_node(f, ni, nj);
    switch (k) {
        case 0: return {out(sw, e.min.x, e.min.y), out(sw, sw.x, e.min.y), sw, out(sw, e.min.x, sw.y)};
        case 1: return {out(se, se.x, e.min.y), out(se, e.max.x, e.min.y), out(se, e.max.x, se.y), se};
        case 2: return {ne, out(ne, e.max.x, ne.y), out(ne, e.max.x, e.max.y), out(ne, ne.x, e.max.y)};
        default: return {out(nw, e.min.x, nw.y), nw, out(nw, nw.x, e.max.y), out(nw, e.min.x, e.max.y)};
    }
}

std::vector<std::array<Vec3, 4>> terrain_skirt(const Scene& scene) {
    const Box2 extent = terrain_extent(scene);
    std::vector<std::array<Vec3, 4>> quads;
    for (size_t k = 0, n = terrain_skirt_count(scene.terrain); k < n; ++k)
        quads.push_back(terrain_skirt_quad(scene.terrain, extent, k));
    return quads;
}

TriangleMesh build_stored_field_terrain(const Scene& scene) {
    const HeightField& f = scene.terrain;
    TriangleMesh mesh;
    mesh.kind = ObjectKind::Terrain;
    for (uint32_t j = 0; j < f.ny; ++j)
        for (uint32_t i = 0; i < f.nx; ++i) mesh.add_vertex(field_node(f, i, j));
    for (uint32_t j = 0; j + 1 < f.ny; ++j)
        for (uint32_t i = 0; i + 1 < f.nx; ++i) {
            const uint32_t v00 = j * f.nx + i, v10 = v00 + 1, v01 = v00 + f.nx, v11 = v01 + 1;
            // The diagonal rule of field_surface_height: (00, 10, 11) and (00, 11, 01).
            mesh.add_triangle(v00, v10, v11, 0, kGround);
            mesh.add_triangle(v00, v11, v01, 0, kGround);
        }
    for (const auto& q : terrain_skirt(scene)) mesh.add_quad(q[0], q[1], q[2], q[3], 0, kGround);
    return mesh;
}

namespace {

// Ray against triangle (a, b, c), Moeller-Trumbore in double; the normal is the
// counter-clockwise side's, as StoredMeshGeometry reports it.
bool ray_triangle(Vec3 a, Vec3 b, Vec3 c, Vec3 o, Vec3 d, double tmin, double tmax, UserHit* hit) {
    const Vec3 e1 = b - a, e2 = c - a;
    const Vec3 p = cross(d, e2);
    const double det = dot(e1, p);
    if (std::abs(det) < 1e-300) return false;
    const double inv = 1.0 / det;
    const Vec3 s = o - a;
    const double u = dot(s, p) * inv;
    if (u < 0 || u > 1) return false;
    const Vec3 q = cross(s, e1);
    const double v = dot(d, q) * inv;
    if (v < 0 || u + v > 1) return false;
    const double t = dot(e2, q) * inv;
    if (!(t >= tmin && t <= tmax)) return false;
    hit->t = t;
    hit->normal = normalize(cross(e1, e2));
    hit->material = kGround;
    return true;
}

// A block's cells are walked in groups of kGroup x kGroup: a group whose height range the ray
// does not meet is crossed in one step instead of kGroup cell steps.
constexpr uint32_t kGroup = 4;
constexpr uint32_t kGroupsAcross = kTerrainBlock / kGroup;
static_assert(kTerrainBlock % kGroup == 0, "a block holds whole groups");

struct HeightRange {
    float lo = std::numeric_limits<float>::max(), hi = -std::numeric_limits<float>::max();
    void add(float h) {
        lo = std::min(lo, h);
        hi = std::max(hi, h);
    }
};

// Whether the ray's height between t_in and t_out meets `range`, padded by 1 mm so that rounding
// never skips a cell with a hit (a false "meets" costs only the triangle tests).
bool meets(double z, double dz, double t_in, double t_out, HeightRange range) {
    const double z_in = z + dz * t_in, z_out = z + dz * t_out;
    return std::max(z_in, z_out) >= range.lo - 1e-3 && std::min(z_in, z_out) <= range.hi + 1e-3;
}

// A 2D DDA: visits the cells of [i0, i1) x [j0, j1) that the line (u + du t, v + dv t) crosses for
// t in [t0, t1], in order, as visit(i, j, t_in, t_out) with the t span inside the cell, until a
// visit returns true (then true). Coordinates are in cell units.
template <typename Visit>
bool walk_cells(double u, double v, double du, double dv, double t0, double t1, uint32_t i0, uint32_t i1,
                uint32_t j0, uint32_t j1, const Visit& visit) {
    const double inf = std::numeric_limits<double>::infinity();
    auto start_cell = [&](double s, double ds, uint32_t lo, uint32_t hi) {
        const double at = std::floor(s + ds * t0);
        return static_cast<uint32_t>(std::clamp(at, static_cast<double>(lo), hi - 1.0));
    };
    uint32_t i = start_cell(u, du, i0, i1), j = start_cell(v, dv, j0, j1);
    const int step_i = du > 0 ? 1 : -1, step_j = dv > 0 ? 1 : -1;
    double next_u = du > 0 ? (i + 1 - u) / du : du < 0 ? (i - u) / du : inf;
    double next_v = dv > 0 ? (j + 1 - v) / dv : dv < 0 ? (j - v) / dv : inf;
    const double delta_u = du != 0 ? std::abs(1 / du) : inf, delta_v = dv != 0 ? std::abs(1 / dv) : inf;
    double t_in = t0;
    for (;;) {
        if (visit(i, j, t_in, std::min({next_u, next_v, t1}))) return true;
        if (next_u < next_v) {
            if (next_u > t1) return false;
            const long ni = static_cast<long>(i) + step_i;
            if (ni < static_cast<long>(i0) || ni >= static_cast<long>(i1)) return false;
            i = static_cast<uint32_t>(ni);
            t_in = next_u;
            next_u += delta_u;
        } else {
            if (next_v > t1) return false;
            const long nj = static_cast<long>(j) + step_j;
            if (nj < static_cast<long>(j0) || nj >= static_cast<long>(j1)) return false;
            j = static_cast<uint32_t>(nj);
            t_in = next_v;
            next_v += delta_v;
        }
    }
}

class ProceduralTerrain : public RenderGeometry {
public:
    explicit ProceduralTerrain(const Scene& scene)
        : field_(scene.terrain), extent_(terrain_extent(scene)), skirt_count_(terrain_skirt_count(field_)) {
        blocks_x_ = (field_.nx - 2) / kTerrainBlock + 1;
        blocks_y_ = (field_.ny - 2) / kTerrainBlock + 1;
        block_range_.resize(static_cast<size_t>(blocks_x_) * blocks_y_);
        group_range_.resize(block_range_.size() * kGroupsAcross * kGroupsAcross);
        // A cell's range is its four nodes'; a group's and a block's, their cells'.
        for (uint32_t j = 0; j + 1 < field_.ny; ++j)
            for (uint32_t i = 0; i + 1 < field_.nx; ++i) {
                const unsigned block = (j / kTerrainBlock) * blocks_x_ + i / kTerrainBlock;
                HeightRange& group = group_range_[group_index(block, (i % kTerrainBlock) / kGroup,
                                                              (j % kTerrainBlock) / kGroup)];
                for (uint32_t n = 0; n < 4; ++n) {
                    const float h = field_node_height(i + n % 2, j + n / 2);
                    group.add(h);
                    block_range_[block].add(h);
                }
            }
    }
    ObjectKind kind() const override { return ObjectKind::Terrain; }
    GeometryMode mode() const override { return GeometryMode::Procedural; }
    uint64_t primitive_count() const override { return block_range_.size() + skirt_count_; }
    uint64_t triangle_count() const override { return 0; }
    size_t buffer_bytes() const override {
        return field_.heights.capacity() * sizeof(float) +
               (block_range_.capacity() + group_range_.capacity()) * sizeof(HeightRange);
    }
    RTCGeometry create_embree_geometry(RTCDevice device) override {
        return new_user_geometry(device, this, primitive_count());
    }
    void complete_hit(const RTCHit& embree_hit, Hit& hit) const override {
        complete_user_hit(embree_hit, ObjectKind::Terrain, 0, hit);
    }

    void bounds(unsigned prim, RTCBounds* out) const;
    bool intersect(unsigned prim, Vec3 o, Vec3 d, double tmin, double tmax, UserHit* hit) const;
    bool occluded(unsigned prim, Vec3 o, Vec3 d, double tmin, double tmax) const {
        UserHit hit;
        return intersect(prim, o, d, tmin, tmax, &hit);
    }

private:
    float field_node_height(uint32_t i, uint32_t j) const {
        return field_.heights[static_cast<size_t>(j) * field_.nx + i];
    }
    static size_t group_index(unsigned block, uint32_t gi, uint32_t gj) {
        return (size_t{block} * kGroupsAcross + gj) * kGroupsAcross + gi;
    }
    // Cells [i0, i1) x [j0, j1) of block `prim`.
    void block_cells(unsigned prim, uint32_t* i0, uint32_t* i1, uint32_t* j0, uint32_t* j1) const {
        const uint32_t bx = prim % blocks_x_, by = prim / blocks_x_;
        *i0 = bx * kTerrainBlock;
        *j0 = by * kTerrainBlock;
        *i1 = std::min(field_.nx - 1, *i0 + kTerrainBlock);
        *j1 = std::min(field_.ny - 1, *j0 + kTerrainBlock);
    }
    bool intersect_cell(uint32_t i, uint32_t j, Vec3 o, Vec3 d, double tmin, double tmax, UserHit* hit) const {
        const Vec3 a = field_node(field_, i, j), b = field_node(field_, i + 1, j);
        const Vec3 c = field_node(field_, i + 1, j + 1), e = field_node(field_, i, j + 1);
        UserHit first, second;
        const bool h1 = ray_triangle(a, b, c, o, d, tmin, tmax, &first);
        const bool h2 = ray_triangle(a, c, e, o, d, tmin, tmax, &second);
        if (!h1 && !h2) return false;
        *hit = (h1 && (!h2 || first.t <= second.t)) ? first : second;
        return true;
    }
    bool intersect_block(unsigned prim, Vec3 o, Vec3 d, double tmin, double tmax, UserHit* hit) const;

    HeightField field_;
    Box2 extent_;
    size_t skirt_count_;
    std::vector<HeightRange> block_range_;
    // kGroupsAcross x kGroupsAcross per block, rows south to north (group_index).
    std::vector<HeightRange> group_range_;
    uint32_t blocks_x_ = 0, blocks_y_ = 0;
};

void ProceduralTerrain::bounds(unsigned prim, RTCBounds* out) const {
    Vec3 lo, hi;
    if (prim < block_range_.size()) {
        uint32_t i0, i1, j0, j1;
        block_cells(prim, &i0, &i1, &j0, &j1);
        const Vec3 a = field_node(field_, i0, j0), b = field_node(field_, i1, j1);
        lo = {a.x, a.y, block_range_[prim].lo};
        hi = {b.x, b.y, block_range_[prim].hi};
    } else {
        const auto q = terrain_skirt_quad(field_, extent_, prim - block_range_.size());
        lo = hi = q[0];
        for (const Vec3& p : q) {
            lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
            hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
        }
    }
    // Padded outward: float rounding must not cut off the surface.
    const double pad = 1e-3 + 1e-6 * std::max({std::abs(lo.x), std::abs(lo.y), std::abs(hi.x), std::abs(hi.y)});
    set_bounds(out, {lo.x - pad, lo.y - pad, lo.z - pad}, {hi.x + pad, hi.y + pad, hi.z + pad});
}

bool ProceduralTerrain::intersect(unsigned prim, Vec3 o, Vec3 d, double tmin, double tmax, UserHit* hit) const {
    if (prim < block_range_.size()) return intersect_block(prim, o, d, tmin, tmax, hit);
    const auto q = terrain_skirt_quad(field_, extent_, prim - block_range_.size());
    UserHit first, second;
    const bool h1 = ray_triangle(q[0], q[1], q[2], o, d, tmin, tmax, &first);
    const bool h2 = ray_triangle(q[0], q[2], q[3], o, d, tmin, tmax, &second);
    if (!h1 && !h2) return false;
    *hit = (h1 && (!h2 || first.t <= second.t)) ? first : second;
    return true;
}

// The block's groups along the ray, then the cells of each group the ray comes within the height
// range of, each cell tested only where the ray meets its own range (most cells a block's box lets
// through lie wholly under the ray). Cells come in the ray's order, so the first cell with a hit
// holds the nearest one.
bool ProceduralTerrain::intersect_block(unsigned prim, Vec3 o, Vec3 d, double tmin, double tmax,
                                        UserHit* hit) const {
    uint32_t i0, i1, j0, j1;
    block_cells(prim, &i0, &i1, &j0, &j1);
    const double u = (o.x - field_.origin.x) / field_.cell, v = (o.y - field_.origin.y) / field_.cell;
    const double du = d.x / field_.cell, dv = d.y / field_.cell;
    double t0 = tmin, t1 = tmax;
    auto clip = [&](double start, double delta, double lo, double hi) {
        if (std::abs(delta) < 1e-300) return start >= lo && start <= hi;
        double ta = (lo - start) / delta, tb = (hi - start) / delta;
        if (ta > tb) std::swap(ta, tb);
        t0 = std::max(t0, ta);
        t1 = std::min(t1, tb);
        return t0 <= t1;
    };
    // To the block's cells, and to where the ray is within the block's heights (padded as in meets).
    const HeightRange block = block_range_[prim];
    if (!clip(u, du, i0, i1) || !clip(v, dv, j0, j1) || !clip(o.z, d.z, block.lo - 1e-3, block.hi + 1e-3))
        return false;
    // Group coordinates are the cell ones over kGroup, a power of two: exact, so a group's edges
    // fall at the same t as its cells'.
    const uint32_t g0 = i0 / kGroup, h0 = j0 / kGroup;
    return walk_cells(u / kGroup, v / kGroup, du / kGroup, dv / kGroup, t0, t1, g0, (i1 + kGroup - 1) / kGroup, h0,
                      (j1 + kGroup - 1) / kGroup, [&](uint32_t gi, uint32_t gj, double g_in, double g_out) {
        if (!meets(o.z, d.z, g_in, g_out, group_range_[group_index(prim, gi - g0, gj - h0)])) return false;
        return walk_cells(u, v, du, dv, g_in, g_out, gi * kGroup, std::min(i1, (gi + 1) * kGroup), gj * kGroup,
                          std::min(j1, (gj + 1) * kGroup), [&](uint32_t i, uint32_t j, double c_in, double c_out) {
            HeightRange cell;
            for (uint32_t n = 0; n < 4; ++n) cell.add(field_node_height(i + n % 2, j + n / 2));
            return meets(o.z, d.z, c_in, c_out, cell) && intersect_cell(i, j, o, d, tmin, tmax, hit);
        });
    });
}

}  // namespace

std::unique_ptr<RenderGeometry> build_procedural_field_terrain(const Scene& scene) {
    return std::make_unique<ProceduralTerrain>(scene);
}

}  // namespace citygen
