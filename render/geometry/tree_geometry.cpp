#include "render/geometry/tree_geometry.h"

#include <algorithm>
#include <cmath>

#include "common/rng.h"
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

// Ray (o + t d) against the ellipsoid with centre c and semi-axes (r, r, h): entry and exit t.
bool ellipsoid_hits(Vec3 o, Vec3 d, Vec3 c, double r, double h, double* t0, double* t1) {
    const Vec3 oc = o - c;
    const Vec3 os{oc.x / r, oc.y / r, oc.z / h}, ds{d.x / r, d.y / r, d.z / h};
    const double a = dot(ds, ds), b = dot(os, ds), cc = dot(os, os) - 1;
    const double disc = b * b - a * cc;
    if (disc < 0 || a <= 0) return false;
    const double s = std::sqrt(disc);
    *t0 = (-b - s) / a;
    *t1 = (-b + s) / a;
    return true;
}

Vec3 ellipsoid_normal(Vec3 p, Vec3 c, double r, double h) {
    const Vec3 q = p - c;
    return normalize(Vec3{q.x / (r * r), q.y / (r * r), q.z / (h * h)});
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
    // Trunk: a vertical cylinder, no caps (its foot is on the ground, its top in the crown).
    {
        const double ox = o.x - s.base.x, oy = o.y - s.base.y;
        const double a = d.x * d.x + d.y * d.y, b = ox * d.x + oy * d.y,
                     c = ox * ox + oy * oy - s.trunk_radius * s.trunk_radius;
        const double disc = b * b - a * c;
        if (a > 0 && disc >= 0) {
            const double root = std::sqrt(disc);
            for (double t : {(-b - root) / a, (-b + root) / a}) {
                const double z = o.z + d.z * t - s.base.z;
                if (z >= 0 && z <= s.trunk_top && t >= tmin && t <= tmax) {
                    const Vec3 p = o + d * t;
                    take(t, normalize(Vec3{p.x - s.base.x, p.y - s.base.y, 0}), kBark);
                    break;
                }
            }
        }
    }
    double t0, t1;
    if (!ellipsoid_hits(o, d, s.crown_centre, s.crown_radius, s.crown_half_height, &t0, &t1)) return found;
    if (t0 > tmax || t1 < tmin) return found;
    // The shell where it has leaves, then the core, then the far shell.
    if (t0 >= tmin && t0 <= tmax && leaf_present(s, o + d * t0)) {
        take(t0, ellipsoid_normal(o + d * t0, s.crown_centre, s.crown_radius, s.crown_half_height), s.leaf_material);
        return true;
    }
    const double cr = s.crown_radius * kTreeCoreScale, ch = s.crown_half_height * kTreeCoreScale;
    double c0, c1;
    if (ellipsoid_hits(o, d, s.crown_centre, cr, ch, &c0, &c1)) {
        const double t = c0 >= tmin ? c0 : c1;
        if (t >= tmin && t <= tmax) {
            take(t, ellipsoid_normal(o + d * t, s.crown_centre, cr, ch), s.leaf_material);
            return true;
        }
    }
    if (t1 >= tmin && t1 <= tmax && leaf_present(s, o + d * t1))
        take(t1, ellipsoid_normal(o + d * t1, s.crown_centre, s.crown_radius, s.crown_half_height), s.leaf_material);
    return found;
}

// ---- procedural ----------------------------------------------------------------------

class ProceduralTrees : public RenderGeometry {
public:
    explicit ProceduralTrees(const Scene& scene) : ground_z_(scene.ground.z) {
        trees_.reserve(scene.trees.size());
        for (const Tree& t : scene.trees)
            trees_.push_back({static_cast<float>(t.position.x), static_cast<float>(t.position.y),
                              static_cast<float>(t.height), static_cast<float>(t.crown_diameter),
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
        const double r = std::max(s.crown_radius, s.trunk_radius) + 1e-3;
        out->lower_x = static_cast<float>(s.base.x - r);
        out->lower_y = static_cast<float>(s.base.y - r);
        out->lower_z = static_cast<float>(s.base.z - 1e-3);
        out->upper_x = static_cast<float>(s.base.x + r);
        out->upper_y = static_cast<float>(s.base.y + r);
        out->upper_z = static_cast<float>(s.crown_centre.z + s.crown_half_height + 1e-3);
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
    // What a tree costs here: 20 bytes (the shape is derived on the fly).
    struct Compact {
        float x, y, height, crown;
        uint8_t leaf_type;
    };
    TreeShape shape(unsigned prim) const {
        const Compact& c = trees_[prim];
        return tree_shape(c.x, c.y, c.height, c.crown, c.leaf_type == static_cast<uint8_t>(LeafType::Needleleaved),
                          ground_z_, prim);
    }

    double ground_z_;
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
            // The facet's point moved onto the true ellipsoid, so the leaf pattern matches the
            // procedural crown's.
            const Vec3 q = o + d * RTCRayN_tfar(args->ray, N, i) - shape.crown_centre;
            const double r = shape.crown_radius, h = shape.crown_half_height;
            const double scale = std::sqrt((q.x * q.x + q.y * q.y) / (r * r) + q.z * q.z / (h * h));
            const Vec3 on_surface = shape.crown_centre + q * (scale > 0 ? 1 / scale : 1.0);
            if (!leaf_present(shape, on_surface)) args->valid[i] = 0;
        }
    }
    std::vector<uint8_t> cut_out_;
    std::vector<TreeShape> shapes_;
};

// An ellipsoid as a UV sphere, counter-clockwise seen from outside.
void add_ellipsoid(TriangleMesh& mesh, std::vector<uint8_t>& cut_out, uint8_t cut, Vec3 c, double r, double h,
                   int segments, int rings, uint32_t object, uint16_t material) {
    const uint32_t first = static_cast<uint32_t>(mesh.vertex_count());
    // Vertices a little outside the surface, so the facets straddle it instead of lying inside.
    const double out = 0.5 * (1 + 1 / std::cos(kPi / segments));
    r *= out;
    h *= 0.5 * (1 + 1 / std::cos(kPi / (2 * rings)));
    for (int k = 0; k <= rings; ++k) {
        const double theta = kPi * k / rings;  // from the top
        for (int j = 0; j < segments; ++j) {
            const double phi = 2 * kPi * j / segments;
            mesh.add_vertex({c.x + r * std::sin(theta) * std::cos(phi), c.y + r * std::sin(theta) * std::sin(phi),
                             c.z + h * std::cos(theta)});
        }
    }
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
                      static_cast<float>(t.crown_diameter), t.leaf_type == LeafType::Needleleaved, scene.ground.z,
                      index);
}

TreeShape tree_shape(float x, float y, float height, float crown, bool needle, double ground_z, uint32_t index) {
    TreeShape s;
    s.base = {x, y, ground_z};
    s.crown_radius = 0.5 * crown;
    s.crown_half_height = needle ? 0.4 * height : std::min(0.35 * height, 0.6 * crown);
    s.crown_centre = {x, y, ground_z + height - s.crown_half_height};
    s.trunk_radius = std::clamp(0.025 * height, 0.08, 0.4);
    s.trunk_top = s.crown_centre.z - ground_z;
    s.leaf_material = needle ? kLeavesNeedle : kLeavesBroad;
    s.noise_seed = static_cast<uint32_t>(index * 2654435761u);
    return s;
}

bool leaf_present(const TreeShape& tree, Vec3 p) {
    const Vec3 q = p - tree.crown_centre;
    const double n = 0.65 * value_noise(q * (1 / 0.7), tree.noise_seed) +
                     0.35 * value_noise(q * (1 / 0.25), tree.noise_seed + 1);
    return n > 0.45;
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
        // Trunk: an 8-sided prism (walls only).
        constexpr int kSides = 8;
        for (int j = 0; j < kSides; ++j) {
            const double a0 = 2 * kPi * j / kSides, a1 = 2 * kPi * (j + 1) / kSides;
            const Vec3 p0{s.base.x + s.trunk_radius * std::cos(a0), s.base.y + s.trunk_radius * std::sin(a0), s.base.z};
            const Vec3 p1{s.base.x + s.trunk_radius * std::cos(a1), s.base.y + s.trunk_radius * std::sin(a1), s.base.z};
            const Vec3 up{0, 0, s.trunk_top};
            mesh.add_quad(p0, p1, p1 + up, p0 + up, i, kBark);
            cut_out.insert(cut_out.end(), {0, 0});
        }
        add_ellipsoid(mesh, cut_out, 1, s.crown_centre, s.crown_radius, s.crown_half_height, 16, 10, i,
                      s.leaf_material);
        add_ellipsoid(mesh, cut_out, 0, s.crown_centre, s.crown_radius * kTreeCoreScale,
                      s.crown_half_height * kTreeCoreScale, 8, 5, i, s.leaf_material);
    }
    return std::make_unique<StoredTrees>(std::move(mesh), std::move(cut_out), std::move(shapes));
}

std::unique_ptr<RenderGeometry> build_procedural_trees(const Scene& scene) {
    return std::make_unique<ProceduralTrees>(scene);
}

}  // namespace citygen
