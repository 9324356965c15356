// Stored mode for street lamps: the lamp shape (lamp_shape.h) as triangles whose facets stay
// within kFacetError of the analytic surfaces the procedural mode hits.
#include <cmath>

#include "render/geometry/lamp_shape.h"
#include "render/geometry/stored_geometry.h"
#include "render/materials/materials.h"

namespace citygen {

namespace {

// Both modes agree within 1 cm in depth, as the trees do (tests/render/cli/procedural_render_test.cpp);
// half a millimetre took 1,720 triangles a lamp, half of a city's stored triangles (docs/rendering.md).
constexpr double kFacetError = 0.002;

// Radius for the vertices of an n-sided polygon around a circle of radius r such that the
// facets straddle the circle (vertices outside by as much as edge midpoints are inside):
// halves the depth error against the analytic surface.
double straddling_radius(double r, double cos_half_step) { return 2 * r / (1 + cos_half_step); }

// The fewest sides that keep facets straddling a circle of radius r within kFacetError of it;
// with `sphere`, an even number for a sphere of that many sides and half as many rings, whose
// facet centres lie deepest (half a step both ways).
int sides_within_error(double r, bool sphere) {
    for (int n = 3;; ++n) {
        const double c = sphere ? std::cos(kPi / n) * std::cos(kPi / n) : std::cos(kPi / n);
        if (r * (1 - c) / (1 + c) <= kFacetError && (!sphere || n % 2 == 0)) return n;
    }
}

Vec3 on_circle(Vec3 center, double r, int i, int n, double z) {
    const double a = 2 * kPi * i / n;
    return {center.x + r * std::cos(a), center.y + r * std::sin(a), z};
}

// Side of a vertical cylinder, normals outward (counter-clockwise seen from outside).
void add_cylinder(Vec3 axis, double r, double z0, double z1, int sides, uint32_t object, uint16_t material,
                  TriangleMesh& mesh) {
    r = straddling_radius(r, std::cos(kPi / sides));
    for (int i = 0; i < sides; ++i)
        mesh.add_quad(on_circle(axis, r, i, sides, z0), on_circle(axis, r, i + 1, sides, z0),
                      on_circle(axis, r, i + 1, sides, z1), on_circle(axis, r, i, sides, z1), object, material);
}

void add_disk(Vec3 axis, double r, double z, int sides, bool up, uint32_t object, uint16_t material,
              TriangleMesh& mesh) {
    r = straddling_radius(r, std::cos(kPi / sides));  // meets the cylinder rim exactly
    const uint32_t centre = mesh.add_vertex({axis.x, axis.y, z});
    const uint32_t first = static_cast<uint32_t>(mesh.vertex_count());
    for (int i = 0; i < sides; ++i) mesh.add_vertex(on_circle(axis, r, i, sides, z));
    for (int i = 0; i < sides; ++i) {
        const uint32_t a = first + i, b = first + (i + 1) % sides;
        if (up) mesh.add_triangle(centre, a, b, object, material);
        else mesh.add_triangle(centre, b, a, object, material);
    }
}

void add_sphere(Vec3 center, double r, int sides, uint32_t object, uint16_t material, TriangleMesh& mesh) {
    const int rings = sides / 2;
    // A facet's centre lies deepest: half a step in both directions.
    r = straddling_radius(r, std::cos(kPi / sides) * std::cos(kPi / (2 * rings)));
    auto point = [&](int ring, int side) {
        const double polar = kPi * ring / rings, a = 2 * kPi * side / sides;
        return center + Vec3{std::sin(polar) * std::cos(a), std::sin(polar) * std::sin(a), std::cos(polar)} * r;
    };
    const uint32_t first = static_cast<uint32_t>(mesh.vertex_count());
    for (int ring = 0; ring <= rings; ++ring)
        for (int side = 0; side < sides; ++side) mesh.add_vertex(point(ring, side));
    auto index = [&](int ring, int side) { return first + ring * sides + side % sides; };
    for (int ring = 0; ring < rings; ++ring) {
        for (int side = 0; side < sides; ++side) {
            // Rings go from the top down, sides counter-clockwise: (ring+1, side) is below.
            const uint32_t a = index(ring, side), b = index(ring + 1, side), c = index(ring + 1, side + 1),
                           d = index(ring, side + 1);
            if (ring > 0) mesh.add_triangle(a, b, d, object, material);
            if (ring + 1 < rings) mesh.add_triangle(b, c, d, object, material);
        }
    }
}

}  // namespace

TriangleMesh build_stored_lamps(const Scene& scene) {
    TriangleMesh mesh;
    mesh.kind = ObjectKind::Lamp;
    const StandingSurface surface(scene);
    // The parts' sides follow their radii, which lamp_shape gives every lamp alike: worked out
    // again only when they change, not for each of a metropolis's lamps.
    LampShape sized;
    int pole_sides = 0, cap_sides = 0, globe_sides = 0;
    for (uint32_t i = 0; i < scene.lamps.size(); ++i) {
        const LampShape s = lamp_shape(scene.lamps[i], lamp_ground(surface, scene.lamps[i]));
        if (i == 0 || s.pole_radius != sized.pole_radius || s.cap_radius != sized.cap_radius ||
            s.globe_radius != sized.globe_radius) {
            sized = s;
            pole_sides = sides_within_error(s.pole_radius, false);
            cap_sides = sides_within_error(s.cap_radius, false);
            globe_sides = sides_within_error(s.globe_radius, true);
        }
        add_cylinder(s.base, s.pole_radius, s.base.z, s.pole_top, pole_sides, i, kLampPole, mesh);
        add_sphere(s.globe_center, s.globe_radius, globe_sides, i, kLampGlobe, mesh);
        add_cylinder(s.base, s.cap_radius, s.cap_bottom, s.cap_top, cap_sides, i, kLampCap, mesh);
        add_disk(s.base, s.cap_radius, s.cap_top, cap_sides, true, i, kLampCap, mesh);
        add_disk(s.base, s.cap_radius, s.cap_bottom, cap_sides, false, i, kLampCap, mesh);
    }
    return mesh;
}

}  // namespace citygen
