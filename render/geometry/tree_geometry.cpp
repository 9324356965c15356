#include "render/geometry/tree_geometry.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <vector>

#include "common/rng.h"
#include "render/geometry/ground.h"
#include "render/materials/materials.h"
#include "render/scene/triangle_mesh.h"
#include "render/scene/user_geometry.h"

namespace citygen {

namespace {

double lattice(int64_t x, int64_t y, int64_t z, uint32_t seed) {
    return hash_to_unit(hash_keys(seed, static_cast<uint64_t>(x), static_cast<uint64_t>(y), static_cast<uint64_t>(z)));
}

double smooth(double t) { return t * t * (3 - 2 * t); }

double value_noise(Vec3 p, uint32_t seed) {
    const double fx = std::floor(p.x), fy = std::floor(p.y), fz = std::floor(p.z);
    const int64_t ix = static_cast<int64_t>(fx), iy = static_cast<int64_t>(fy), iz = static_cast<int64_t>(fz);
    const double tx = smooth(p.x - fx), ty = smooth(p.y - fy), tz = smooth(p.z - fz);
    double v[2][2][2];
    for (int a = 0; a < 2; ++a)
        for (int b = 0; b < 2; ++b)
            for (int c = 0; c < 2; ++c) v[a][b][c] = lattice(ix + a, iy + b, iz + c, seed);
    auto lerp = [](double a, double b, double t) { return a + (b - a) * t; };
    const double x00 = lerp(v[0][0][0], v[1][0][0], tx), x10 = lerp(v[0][1][0], v[1][1][0], tx);
    const double x01 = lerp(v[0][0][1], v[1][0][1], tx), x11 = lerp(v[0][1][1], v[1][1][1], tx);
    return lerp(lerp(x00, x10, ty), lerp(x01, x11, ty), tz);
}

// A convex polyhedron as the planes n . q <= e of its facets, in a frame where a tree part is
// a fixed unit shape (unit_shell, unit_trunk): a ray's entry and exit are the last
// entering and the first leaving plane. Exact where the stored triangles are (the facets' own
// planes), so both modes agree to float precision.
struct Plane {
    Vec3 n;  // outward, unit in the unit frame
    double e;
};

struct Crossing {
    double t_in = 0, t_out = 0;
    int face_in = -1, face_out = -1;
};

bool clip_by_planes(const std::vector<Plane>& planes, Vec3 o, Vec3 d, Crossing* out) {
    double t_in = -std::numeric_limits<double>::infinity(), t_out = std::numeric_limits<double>::infinity();
    int face_in = -1, face_out = -1;
    for (size_t i = 0; i < planes.size(); ++i) {
        const Plane& p = planes[i];
        const double num = p.e - dot(p.n, o), den = dot(p.n, d);
        if (den < 0) {
            // entering: t = num / den, kept when larger (divide only then)
            if (num < t_in * den) {
                t_in = num / den;
                face_in = static_cast<int>(i);
            }
        } else if (den > 0) {
            if (num < t_out * den) {
                t_out = num / den;
                face_out = static_cast<int>(i);
            }
        } else if (num < 0) {
            return false;  // parallel and outside
        }
        if (t_in > t_out) return false;
    }
    if (face_in < 0 || face_out < 0) return false;
    *out = {t_in, t_out, face_in, face_out};
    return true;
}

Plane plane_of(Vec3 a, Vec3 b, Vec3 c) {
    const Vec3 n = normalize(cross(b - a, c - a));
    return {n, dot(n, a)};
}

// The facets of a crown shell, in the frame where its centre is 0 and its semi-axes are 1: the
// planes of crown_vertex's triangles (a quad between two rings is planar: it is symmetric
// about its middle meridian).
struct UnitShell {
    std::vector<Plane> planes;
    double outer_r, outer_h;  // semi-axes of the ellipsoid through its vertices
};

UnitShell unit_shell(CrownFacets f) {
    std::vector<Plane> planes;
    auto v = [&](int k, int j) { return crown_vertex({0, 0, 0}, 1, 1, f, k, j % f.segments); };
    for (int k = 0; k < f.rings; ++k)
        for (int j = 0; j < f.segments; ++j)
            planes.push_back(k > 0 ? plane_of(v(k, j), v(k + 1, j), v(k, j + 1))
                                   : plane_of(v(k, j + 1), v(k + 1, j), v(k + 1, j + 1)));
    return {planes, v(1, 0).x / std::sin(kPi / f.rings), v(0, 0).z};
}

const UnitShell& shell_facets() {
    static const UnitShell shell = unit_shell(kShellFacets);
    return shell;
}
const UnitShell& core_facets() {
    static const UnitShell core = unit_shell(kCoreFacets);
    return core;
}
// The trunk's side walls (an infinite prism; its height is checked at the crossing), in the
// frame where its foot's centre is 0 and its radius 1.
const std::vector<Plane>& unit_trunk() {
    static const std::vector<Plane> planes = [] {
        TreeShape unit;
        unit.base = {0, 0, 0};
        unit.trunk_radius = 1;
        std::vector<Plane> p;
        for (int j = 0; j < kTrunkSides; ++j) {
            const Vec3 a = trunk_vertex(unit, j), b = trunk_vertex(unit, j + 1);
            p.push_back(plane_of(a, b, b + Vec3{0, 0, 1}));
        }
        return p;
    }();
    return planes;
}

// Ray against a crown shell with centre c and semi-axes (r, r, h) (t as in world space); the
// normals returned are the world facets' outward unit normals.
struct ShellCrossing {
    double t_in, t_out;
    Vec3 n_in, n_out;
};

bool shell_hits(const UnitShell& unit, Vec3 o, Vec3 d, Vec3 c, double r, double h, ShellCrossing* out) {
    const Vec3 oc = o - c;
    const Vec3 os{oc.x / r, oc.y / r, oc.z / h}, ds{d.x / r, d.y / r, d.z / h};
    // Early out: the polyhedron lies inside the ellipsoid through its vertices.
    const double gr = unit.outer_r, gh = unit.outer_h;
    const Vec3 og{os.x / gr, os.y / gr, os.z / gh}, dg{ds.x / gr, ds.y / gr, ds.z / gh};
    const double a = dot(dg, dg), b = dot(og, dg), cc = dot(og, og) - 1;
    if (a <= 0 || b * b - a * cc < 0) return false;
    Crossing x;
    if (!clip_by_planes(unit.planes, os, ds, &x)) return false;
    auto world = [&](Vec3 n) { return normalize(Vec3{n.x / r, n.y / r, n.z / h}); };
    *out = {x.t_in, x.t_out, world(unit.planes[x.face_in].n), world(unit.planes[x.face_out].n)};
    return true;
}

// Closest surface of a tree along the ray in [tmin, tmax].
struct TreeHit {
    double t = 0;
    Vec3 normal;
    uint16_t material = 0;
};

bool intersect_tree(const TreeShape& s, Vec3 o, Vec3 d, double tmin, double tmax, TreeHit* hit) {
    bool found = false;
    auto take = [&](double t, Vec3 n, uint16_t m) {
        if (t >= tmin && t <= tmax) {
            tmax = t;
            *hit = {t, n, m};
            found = true;
        }
    };
    // Trunk: the prism's walls, no caps (its foot is on the ground, its top in the core).
    {
        const double tr = s.trunk_radius;
        const Vec3 os{(o.x - s.base.x) / tr, (o.y - s.base.y) / tr, 0}, ds{d.x / tr, d.y / tr, 0};
        Crossing x;
        if (clip_by_planes(unit_trunk(), os, ds, &x)) {
            const std::vector<Plane>& walls = unit_trunk();
            for (int side = 0; side < 2; ++side) {
                const double t = side == 0 ? x.t_in : x.t_out;
                const double z = o.z + d.z * t - s.base.z;
                if (z >= 0 && z <= s.trunk_top && t >= tmin && t <= tmax) {
                    take(t, walls[side == 0 ? x.face_in : x.face_out].n, kBark);
                    break;
                }
            }
        }
    }
    ShellCrossing shell;
    if (!shell_hits(shell_facets(), o, d, s.crown_centre, s.crown_radius, s.crown_half_height, &shell))
        return found;
    if (shell.t_in > tmax || shell.t_out < tmin) return found;
    // The shell where it has leaves, then the core, then the far shell.
    if (shell.t_in >= tmin && shell.t_in <= tmax && leaf_at(s, o + d * shell.t_in)) {
        take(shell.t_in, shell.n_in, s.leaf_material);
        return true;
    }
    ShellCrossing core;
    if (shell_hits(core_facets(), o, d, s.crown_centre, s.crown_radius * kTreeCoreScale,
                   s.crown_half_height * kTreeCoreScale, &core)) {
        const bool front = core.t_in >= tmin;
        const double t = front ? core.t_in : core.t_out;
        if (t >= tmin && t <= tmax) {
            take(t, front ? core.n_in : core.n_out, s.leaf_material);
            return true;
        }
    }
    if (shell.t_out >= tmin && shell.t_out <= tmax && leaf_at(s, o + d * shell.t_out))
        take(shell.t_out, shell.n_out, s.leaf_material);
    return found;
}

// ---- procedural ----------------------------------------------------------------------

class ProceduralTrees : public RenderGeometry {
public:
    explicit ProceduralTrees(const Scene& scene) {
        trees_.reserve(scene.trees.size());
        for (const Tree& t : scene.trees)
            trees_.push_back({static_cast<float>(t.position.x), static_cast<float>(t.position.y),
                              static_cast<float>(t.height), static_cast<float>(t.crown_diameter),
                              static_cast<float>(ground_height(scene, t.position.x, t.position.y)),
                              static_cast<uint8_t>(t.leaf_type)});
    }
    ObjectKind kind() const override { return ObjectKind::Tree; }
    GeometryMode mode() const override { return GeometryMode::Procedural; }
    uint64_t primitive_count() const override { return trees_.size(); }
    uint64_t triangle_count() const override { return 0; }
    size_t buffer_bytes() const override { return trees_.capacity() * sizeof(Compact); }
    RTCGeometry create_embree_geometry(RTCDevice device) override {
        return new_user_geometry(device, this, trees_.size());
    }
    void complete_hit(const RTCHit& embree_hit, Hit& hit) const override {
        complete_user_hit(embree_hit, ObjectKind::Tree, embree_hit.primID, hit);
    }

    // What the Embree callbacks (user_geometry.h) compute per tree.
    void bounds(unsigned prim, RTCBounds* out) const {
        const TreeShape s = shape(prim);
        // The facets' vertices lie a little outside the crown's ellipsoid.
        const UnitShell& shell = shell_facets();
        const double r = std::max(s.crown_radius * shell.outer_r, s.trunk_radius) + 1e-3;
        set_bounds(out, {s.base.x - r, s.base.y - r, s.base.z - 1e-3},
                   {s.base.x + r, s.base.y + r, s.crown_centre.z + s.crown_half_height * shell.outer_h + 1e-3});
    }
    bool intersect(unsigned prim, Vec3 origin, Vec3 direction, double tmin, double tmax, UserHit* hit) const {
        TreeHit found;
        if (!intersect_tree(shape(prim), origin, direction, tmin, tmax, &found)) return false;
        hit->t = found.t;
        hit->normal = found.normal;
        hit->material = found.material;
        return true;
    }
    bool occluded(unsigned prim, Vec3 origin, Vec3 direction, double tmin, double tmax) const {
        TreeHit found;
        return intersect_tree(shape(prim), origin, direction, tmin, tmax, &found);
    }

private:
    // What a tree costs here: 24 bytes (the shape is derived on the fly).
    struct Compact {
        float x, y, height, crown, ground_z;
        uint8_t leaf_type;
    };
    TreeShape shape(unsigned prim) const {
        const Compact& c = trees_[prim];
        return tree_shape(c.x, c.y, c.height, c.crown, c.leaf_type == static_cast<uint8_t>(LeafType::Needleleaved),
                          c.ground_z);
    }

    std::vector<Compact> trees_;
};

// ---- stored --------------------------------------------------------------------------

class StoredTrees : public StoredMeshGeometry {
public:
    StoredTrees(TriangleMesh mesh, std::vector<uint8_t> cut_out, std::vector<TreeShape> shapes)
        : StoredMeshGeometry(std::move(mesh)), cut_out_(std::move(cut_out)), shapes_(std::move(shapes)) {}
    RTCGeometry create_embree_geometry(RTCDevice device) override {
        RTCGeometry g = StoredMeshGeometry::create_embree_geometry(device);
        rtcSetGeometryUserData(g, this);
        rtcSetGeometryIntersectFilterFunction(g, filter);
        rtcSetGeometryOccludedFilterFunction(g, filter);
        return g;
    }
    size_t buffer_bytes() const override {
        return StoredMeshGeometry::buffer_bytes() + cut_out_.capacity() + shapes_.capacity() * sizeof(TreeShape);
    }

private:
    // Rejects hits on the crown shell where the leaf noise leaves a gap.
    static void filter(const RTCFilterFunctionNArguments* args) {
        const auto* self = static_cast<const StoredTrees*>(args->geometryUserPtr);
        const unsigned N = args->N;
        for (unsigned i = 0; i < N; ++i) {
            if (args->valid[i] != -1) continue;
            const unsigned prim = RTCHitN_primID(args->hit, N, i);
            if (!self->cut_out_[prim]) continue;
            const Vec3 o{RTCRayN_org_x(args->ray, N, i), RTCRayN_org_y(args->ray, N, i), RTCRayN_org_z(args->ray, N, i)};
            const Vec3 d{RTCRayN_dir_x(args->ray, N, i), RTCRayN_dir_y(args->ray, N, i), RTCRayN_dir_z(args->ray, N, i)};
            const TreeShape& shape = self->shapes_[self->stored_mesh()->face_object[prim]];
            if (!leaf_at(shape, o + d * RTCRayN_tfar(args->ray, N, i))) args->valid[i] = 0;
        }
    }
    std::vector<uint8_t> cut_out_;
    std::vector<TreeShape> shapes_;
};

// A crown shell (crown_vertex) as triangles, counter-clockwise seen from outside.
void add_shell(TriangleMesh& mesh, std::vector<uint8_t>& cut_out, uint8_t cut, Vec3 c, double r, double h,
               CrownFacets facets, uint32_t object, uint16_t material) {
    const int segments = facets.segments, rings = facets.rings;
    const uint32_t first = static_cast<uint32_t>(mesh.vertex_count());
    for (int k = 0; k <= rings; ++k)
        for (int j = 0; j < segments; ++j) mesh.add_vertex(crown_vertex(c, r, h, facets, k, j));
    auto v = [&](int k, int j) { return first + static_cast<uint32_t>(k * segments + (j % segments)); };
    for (int k = 0; k < rings; ++k)
        for (int j = 0; j < segments; ++j) {
            if (k > 0) {
                mesh.add_triangle(v(k, j), v(k + 1, j), v(k, j + 1), object, material);
                cut_out.push_back(cut);
            }
            if (k + 1 < rings) {
                mesh.add_triangle(v(k, j + 1), v(k + 1, j), v(k + 1, j + 1), object, material);
                cut_out.push_back(cut);
            }
        }
}

}  // namespace

TreeShape tree_shape(const Scene& scene, uint32_t index) {
    const Tree& t = scene.trees[index];
    return tree_shape(static_cast<float>(t.position.x), static_cast<float>(t.position.y), static_cast<float>(t.height),
                      static_cast<float>(t.crown_diameter), t.leaf_type == LeafType::Needleleaved,
                      ground_height(scene, t.position.x, t.position.y));
}

TreeShape tree_shape(float x, float y, float height, float crown, bool needle, double ground_z) {
    TreeShape s;
    s.base = {x, y, ground_z};
    s.crown_radius = 0.5 * crown;
    s.crown_half_height = needle ? 0.4 * height : std::min(0.35 * height, 0.6 * crown);
    s.crown_centre = {x, y, ground_z + height - s.crown_half_height};
    s.trunk_radius = std::clamp(0.025 * height, 0.08, 0.4);
    s.trunk_top = s.crown_centre.z - ground_z;
    s.leaf_material = needle ? kLeavesNeedle : kLeavesBroad;
    // The leaves follow where the tree stands, not its place in the scene's list: a tile of the
    // farm lists a forest's trees in another order than one parse of the region does.
    uint32_t xb, yb;
    std::memcpy(&xb, &x, sizeof xb);
    std::memcpy(&yb, &y, sizeof yb);
    s.noise_seed = static_cast<uint32_t>(hash_keys(0, xb, yb));
    return s;
}

Vec3 trunk_vertex(const TreeShape& s, int j) {
    const double a = 2 * kPi * j / kTrunkSides;
    return {s.base.x + s.trunk_radius * std::cos(a), s.base.y + s.trunk_radius * std::sin(a), s.base.z};
}

Vec3 crown_vertex(Vec3 c, double r, double h, CrownFacets facets, int k, int j) {
    // Scaled so a facet's middle and its vertices are about equally far from the true surface.
    r *= 0.5 * (1 + 1 / std::cos(kPi / facets.segments));
    h *= 0.5 * (1 + 1 / std::cos(kPi / (2 * facets.rings)));
    const double theta = kPi * k / facets.rings;  // from the top
    const double phi = 2 * kPi * j / facets.segments;
    return {c.x + r * std::sin(theta) * std::cos(phi), c.y + r * std::sin(theta) * std::sin(phi),
            c.z + h * std::cos(theta)};
}

bool leaf_present(const TreeShape& tree, Vec3 p) {
    const Vec3 q = p - tree.crown_centre;
    const double n = 0.65 * value_noise(q * (1 / 0.7), tree.noise_seed) +
                     0.35 * value_noise(q * (1 / 0.25), tree.noise_seed + 1);
    return n > 0.45;
}

bool leaf_at(const TreeShape& tree, Vec3 p) {
    const Vec3 q = p - tree.crown_centre;
    const double r = tree.crown_radius, h = tree.crown_half_height;
    const double scale = std::sqrt((q.x * q.x + q.y * q.y) / (r * r) + q.z * q.z / (h * h));
    return leaf_present(tree, tree.crown_centre + q * (scale > 0 ? 1 / scale : 1.0));
}

std::unique_ptr<RenderGeometry> build_stored_trees(const Scene& scene) {
    TriangleMesh mesh;
    mesh.kind = ObjectKind::Tree;
    std::vector<uint8_t> cut_out;
    std::vector<TreeShape> shapes;
    shapes.reserve(scene.trees.size());
    for (uint32_t i = 0; i < scene.trees.size(); ++i) {
        const TreeShape s = tree_shape(scene, i);
        shapes.push_back(s);
        // Trunk: the prism's walls.
        for (int j = 0; j < kTrunkSides; ++j) {
            const Vec3 p0 = trunk_vertex(s, j), p1 = trunk_vertex(s, j + 1);
            const Vec3 up{0, 0, s.trunk_top};
            mesh.add_quad(p0, p1, p1 + up, p0 + up, i, kBark);
            cut_out.insert(cut_out.end(), {0, 0});
        }
        add_shell(mesh, cut_out, 1, s.crown_centre, s.crown_radius, s.crown_half_height, kShellFacets, i,
                  s.leaf_material);
        add_shell(mesh, cut_out, 0, s.crown_centre, s.crown_radius * kTreeCoreScale,
                  s.crown_half_height * kTreeCoreScale, kCoreFacets, i, s.leaf_material);
    }
    return std::make_unique<StoredTrees>(std::move(mesh), std::move(cut_out), std::move(shapes));
}

std::unique_ptr<RenderGeometry> build_procedural_trees(const Scene& scene) {
    return std::make_unique<ProceduralTrees>(scene);
}

}  // namespace citygen
