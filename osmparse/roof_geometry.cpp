#include "roof_geometry.h"

#include <algorithm>
#include <cmath>

#include "roof_skeleton.h"

namespace citygen {

namespace {

constexpr double kPi = 3.141592653589793;

// A height above the eaves that varies linearly over the plane: f(p) = a x + b y + c.
struct Plane {
    double a = 0, b = 0, c = 0;
    double at(Vec2 p) const { return a * p.x + b * p.y + c; }
};

// The plane through two points of a profile across the frame: height h0 at t = t0, h1 at t = t1,
// constant along the frame's `along` axis.
Plane across_plane(const RoofFrame& f, double ta, double ha, double tb, double hb) {
    const double slope = (hb - ha) / (tb - ta);  // per metre of t
    // f(p) = ha + slope * (t(p) - ta), t(p) = dot(p - centre, across).
    Plane p;
    p.a = slope * f.across.x;
    p.b = slope * f.across.y;
    p.c = ha + slope * (-dot(f.centre, f.across) - ta);
    return p;
}
Plane along_plane(const RoofFrame& f, double sa, double ha, double sb, double hb) {
    const double slope = (hb - ha) / (sb - sa);
    Plane p;
    p.a = slope * f.along.x;
    p.b = slope * f.along.y;
    p.c = ha + slope * (-dot(f.centre, f.along) - sa);
    return p;
}

// The part of `ring` where g(p) <= 0 (Sutherland-Hodgman; exact for convex rings).
Ring clip(const Ring& ring, const Plane& g) {
    Ring out;
    for (size_t i = 0, n = ring.size(); i < n; ++i) {
        const Vec2 p = ring[i], q = ring[(i + 1) % n];
        const double gp = g.at(p), gq = g.at(q);
        if (gp <= 0) out.push_back(p);
        if ((gp < 0 && gq > 0) || (gp > 0 && gq < 0)) out.push_back(p + (q - p) * (gp / (gp - gq)));
    }
    return out;
}

Ring without_repeats(const Ring& ring) {
    Ring out;
    for (Vec2 p : ring)
        if (out.empty() || length(p - out.back()) > 1e-6) out.push_back(p);
    while (out.size() > 1 && length(out.front() - out.back()) <= 1e-6) out.pop_back();
    return out;
}

RoofFace lift(const Ring& ring, const Plane& plane, double eaves_z) {
    RoofFace face;
    for (Vec2 p : ring) face.points.push_back({p.x, p.y, eaves_z + plane.at(p)});
    return face;
}

// The roof surface min over `planes` on a convex footprint: each plane's face is the footprint
// where that plane is the lowest.
std::vector<RoofFace> lower_envelope(const Ring& outer, const std::vector<Plane>& planes, double eaves_z) {
    std::vector<RoofFace> faces;
    for (size_t i = 0; i < planes.size(); ++i) {
        Ring piece = outer;
        for (size_t j = 0; j < planes.size() && piece.size() >= 3; ++j) {
            if (j == i) continue;
            const Plane diff{planes[i].a - planes[j].a, planes[i].b - planes[j].b, planes[i].c - planes[j].c};
            piece = clip(piece, diff);
        }
        piece = without_repeats(piece);
        if (piece.size() < 3 || signed_area(piece) < 1e-4) continue;
        faces.push_back(lift(piece, planes[i], eaves_z));
    }
    return faces;
}

// A concave profile across the frame, given as (t fraction in [0, 1], height fraction) points
// from one eave to the other, as one plane per segment (scaled by the roof height).
std::vector<Plane> profile_planes(const RoofFrame& f, const std::vector<std::pair<double, double>>& profile,
                                  double height) {
    std::vector<Plane> planes;
    for (size_t k = 0; k + 1 < profile.size(); ++k) {
        const double ta = f.t0 + profile[k].first * f.width(), tb = f.t0 + profile[k + 1].first * f.width();
        planes.push_back(across_plane(f, ta, profile[k].second * height, tb, profile[k + 1].second * height));
    }
    return planes;
}

Vec2 area_centroid(const Ring& ring) {
    double a = 0;
    Vec2 c{0, 0};
    const Vec2 o = ring[0];  // relative to a vertex: fewer digits lost
    for (size_t i = 0, n = ring.size(); i < n; ++i) {
        const Vec2 p = ring[i] - o, q = ring[(i + 1) % n] - o;
        const double w = cross(p, q);
        a += w;
        c = c + (p + q) * w;
    }
    if (std::fabs(a) < 1e-12) return o;
    return o + c * (1.0 / (3.0 * a));
}

std::vector<RoofFace> pyramid(const Ring& outer, double eaves_z, double height) {
    const Vec2 apex = area_centroid(outer);
    std::vector<RoofFace> faces;
    for (size_t i = 0, n = outer.size(); i < n; ++i) {
        const Vec2 a = outer[i], b = outer[(i + 1) % n];
        faces.push_back({{{a.x, a.y, eaves_z}, {b.x, b.y, eaves_z}, {apex.x, apex.y, eaves_z + height}},
                         RoofFaceKind::Roof});
    }
    return faces;
}

// A surface of revolution over a convex footprint: ring k is the footprint scaled by r_k about
// its centroid at height z_k (fractions of the roof height). Each band between two rings is made
// of trapezoids (their top and bottom edges are parallel), so every face is planar.
std::vector<RoofFace> revolution(const Ring& outer, double eaves_z, double height,
                                 const std::vector<std::pair<double, double>>& profile) {
    const Vec2 c = area_centroid(outer);
    std::vector<RoofFace> faces;
    auto at = [&](Vec2 v, size_t k) {
        const Vec2 p = c + (v - c) * profile[k].first;
        return Vec3{p.x, p.y, eaves_z + profile[k].second * height};
    };
    for (size_t k = 0; k + 1 < profile.size(); ++k)
        for (size_t i = 0, n = outer.size(); i < n; ++i) {
            const Vec2 a = outer[i], b = outer[(i + 1) % n];
            RoofFace face;
            face.points = {at(a, k), at(b, k)};
            if (profile[k + 1].first > 0) face.points.push_back(at(b, k + 1));
            face.points.push_back(at(a, k + 1));
            faces.push_back(std::move(face));
        }
    return faces;
}

bool hipped(const Ring& outer, const std::vector<Ring>& holes, double eaves_z, double height,
            std::vector<RoofFace>* faces, std::string* why) {
    std::vector<SkeletonFace> skeleton;
    if (!straight_skeleton_faces(outer, holes, &skeleton)) {
        *why = "straight skeleton failed";
        return false;
    }
    double last = 0;
    for (const SkeletonFace& f : skeleton)
        for (double t : f.times) last = std::max(last, t);
    if (!(last > 1e-6) || !std::isfinite(last)) {
        *why = "straight skeleton failed";
        return false;
    }
    const double slope = height / last;
    for (const SkeletonFace& f : skeleton) {
        RoofFace face;
        for (size_t i = 0; i < f.points.size(); ++i)
            face.points.push_back({f.points[i].x, f.points[i].y, eaves_z + slope * f.times[i]});
        Ring flat;
        for (Vec3 p : face.points) flat.push_back({p.x, p.y});
        if (signed_area(flat) < 0) std::reverse(face.points.begin(), face.points.end());
        if (std::fabs(signed_area(flat)) < 1e-6) continue;
        faces->push_back(std::move(face));
    }
    return true;
}

}  // namespace

RoofFrame roof_frame(const Ring& outer, const RoofSpec& spec) {
    RoofFrame f;
    Vec2 along{1, 0};
    if (spec.has_direction) {
        along = perp_left(spec.direction);  // the ridge runs across the slope's direction
    } else {
        // Minimum-area rectangle over the edge directions; the ridge follows its long side.
        double best = 1e300;
        for (size_t i = 0, n = outer.size(); i < n; ++i) {
            const Vec2 d = normalize(outer[(i + 1) % n] - outer[i]);
            if (length(d) == 0) continue;
            const Vec2 e = perp_left(d);
            double s0 = 1e300, s1 = -1e300, t0 = 1e300, t1 = -1e300;
            for (Vec2 p : outer) {
                s0 = std::min(s0, dot(p, d)); s1 = std::max(s1, dot(p, d));
                t0 = std::min(t0, dot(p, e)); t1 = std::max(t1, dot(p, e));
            }
            const double area = (s1 - s0) * (t1 - t0);
            if (area < best - 1e-9) {
                best = area;
                along = (s1 - s0 >= t1 - t0) ? d : e;
            }
        }
        if (spec.across) along = perp_left(along);
    }
    f.along = along;
    f.across = perp_left(along);
    f.centre = outer.empty() ? Vec2{0, 0} : outer[0];
    f.s0 = f.t0 = 1e300;
    f.s1 = f.t1 = -1e300;
    for (Vec2 p : outer) {
        const double s = dot(p - f.centre, f.along), t = dot(p - f.centre, f.across);
        f.s0 = std::min(f.s0, s); f.s1 = std::max(f.s1, s);
        f.t0 = std::min(f.t0, t); f.t1 = std::max(f.t1, t);
    }
    return f;
}

bool make_roof_faces(const Ring& outer, const std::vector<Ring>& holes, const RoofSpec& spec,
                     std::vector<RoofFace>* faces, RoofShape* built, std::string* why) {
    faces->clear();
    *built = spec.shape;
    if (spec.shape == RoofShape::Flat) return true;
    if (outer.size() < 3 || !(spec.height > 0)) {
        *why = "degenerate footprint";
        return false;
    }
    const double z = spec.eaves_z, h = spec.height;
    const bool convex = holes.empty() && ring_is_convex(outer);
    const RoofFrame f = roof_frame(outer, spec);
    if (!(f.width() > 0.1) || !(f.length() > 0.1)) {
        *why = "degenerate footprint";
        return false;
    }
    switch (spec.shape) {
        case RoofShape::Flat: return true;
        case RoofShape::Hipped: return hipped(outer, holes, z, h, faces, why);
        case RoofShape::Skillion: {
            if (!holes.empty()) break;
            // With a direction the frame's across axis points uphill (roof_frame), so the top is
            // at t1; without one, the long side at t0 is the high one.
            const Plane plane = spec.has_direction ? across_plane(f, f.t0, 0, f.t1, h)
                                                   : across_plane(f, f.t0, h, f.t1, 0);
            faces->push_back(lift(outer, plane, z));
            return true;
        }
        case RoofShape::Pyramidal:
            if (!convex) break;
            *faces = pyramid(outer, z, h);
            return true;
        case RoofShape::Dome:
        case RoofShape::Onion: {
            if (!convex) break;
            std::vector<std::pair<double, double>> profile;
            if (spec.shape == RoofShape::Dome) {
                for (int k = 0; k <= 6; ++k) {
                    const double a = 0.5 * kPi * k / 6;
                    profile.push_back({k == 6 ? 0.0 : std::cos(a), std::sin(a)});
                }
            } else {  // narrow neck, widest a quarter up, then an S curve to a point
                profile = {{1.0, 0.0},  {0.8, 0.0},  {0.92, 0.08}, {1.0, 0.2},  {0.95, 0.32}, {0.8, 0.45},
                           {0.55, 0.6}, {0.3, 0.75}, {0.12, 0.88}, {0.04, 0.95}, {0.0, 1.0}};
            }
            *faces = revolution(outer, z, h, profile);
            return true;
        }
        default: break;
    }
    if (!convex) {
        // Gables, ridges and curves across a bent or holed footprint: the skeleton's hipped roof
        // (what a courtyard block's wings look like anyway).
        *built = RoofShape::Hipped;
        return hipped(outer, holes, z, h, faces, why);
    }
    std::vector<Plane> planes;
    switch (spec.shape) {
        case RoofShape::Gabled: planes = profile_planes(f, {{0, 0}, {0.5, 1}, {1, 0}}, h); break;
        case RoofShape::Gambrel:
            planes = profile_planes(f, {{0, 0}, {0.18, 0.6}, {0.5, 1}, {0.82, 0.6}, {1, 0}}, h);
            break;
        case RoofShape::Round: {
            std::vector<std::pair<double, double>> profile;
            for (int k = 0; k <= 8; ++k) {
                const double a = kPi * k / 8;
                profile.push_back({0.5 - 0.5 * std::cos(a), std::sin(a)});
            }
            planes = profile_planes(f, profile, h);
            break;
        }
        case RoofShape::HalfHipped: {
            planes = profile_planes(f, {{0, 0}, {0.5, 1}, {1, 0}}, h);
            // Small hips cut the top of each gable: from 60% of the height at the end walls,
            // rising as steeply as the main slopes.
            const double run = 0.4 * 0.5 * f.width();
            planes.push_back(along_plane(f, f.s0, 0.6 * h, f.s0 + run, h));
            planes.push_back(along_plane(f, f.s1, 0.6 * h, f.s1 - run, h));
            break;
        }
        case RoofShape::Mansard: {
            // Steep lower slopes on all four sides up to 75% of the height, then shallow ones.
            const double half = 0.5 * f.width(), steep = 0.2 * half;
            planes.push_back(across_plane(f, f.t0, 0, f.t0 + steep, 0.75 * h));
            planes.push_back(across_plane(f, f.t1, 0, f.t1 - steep, 0.75 * h));
            planes.push_back(across_plane(f, f.t0 + steep, 0.75 * h, f.t0 + half, h));
            planes.push_back(across_plane(f, f.t1 - steep, 0.75 * h, f.t1 - half, h));
            planes.push_back(along_plane(f, f.s0, 0, f.s0 + steep, 0.75 * h));
            planes.push_back(along_plane(f, f.s1, 0, f.s1 - steep, 0.75 * h));
            planes.push_back(along_plane(f, f.s0 + steep, 0.75 * h, f.s0 + half, h));
            planes.push_back(along_plane(f, f.s1 - steep, 0.75 * h, f.s1 - half, h));
            break;
        }
        default: *why = "unknown shape"; return false;
    }
    *faces = lower_envelope(outer, planes, z);
    if (faces->empty()) {
        *why = "no face left";
        return false;
    }
    return true;
}

std::vector<RoofFace> gable_walls(const Ring& outer, const std::vector<Ring>& holes,
                                  const std::vector<RoofFace>& roof, double eaves_z) {
    std::vector<RoofFace> walls;
    auto edge_walls = [&](const Ring& ring, bool building_on_left) {
        for (size_t i = 0, n = ring.size(); i < n; ++i) {
            Vec2 a = ring[i], b = ring[(i + 1) % n];
            if (!building_on_left) std::swap(a, b);
            const Vec2 ab = b - a;
            const double len2 = dot(ab, ab);
            if (len2 <= 0) continue;
            // The roof edge over this wall: every roof vertex on the segment, by position along it.
            std::vector<std::pair<double, double>> profile;  // (t in [0, 1], z)
            for (const RoofFace& face : roof)
                for (Vec3 p : face.points) {
                    const Vec2 q{p.x, p.y};
                    const double t = dot(q - a, ab) / len2;
                    if (t < -1e-6 || t > 1 + 1e-6) continue;
                    if (std::fabs(cross(ab, q - a)) / std::sqrt(len2) > 1e-3) continue;
                    profile.push_back({std::clamp(t, 0.0, 1.0), p.z});
                }
            std::sort(profile.begin(), profile.end());
            double highest = eaves_z;
            for (const auto& [t, pz] : profile) highest = std::max(highest, pz);
            if (highest < eaves_z + 1e-3) continue;
            // Seen from outside (the right of a->b): along the eaves a->b, then back over the roof edge.
            RoofFace wall;
            wall.kind = RoofFaceKind::Gable;
            wall.points = {{a.x, a.y, eaves_z}, {b.x, b.y, eaves_z}};
            for (auto it = profile.rbegin(); it != profile.rend(); ++it) {
                const Vec2 q = a + ab * it->first;
                const Vec3 p{q.x, q.y, std::max(it->second, eaves_z)};
                const Vec3& last = wall.points.back();
                if (length(p - last) < 1e-4) continue;
                wall.points.push_back(p);
            }
            while (wall.points.size() > 2 && length(wall.points.back() - wall.points.front()) < 1e-4)
                wall.points.pop_back();
            if (wall.points.size() >= 3) walls.push_back(std::move(wall));
        }
    };
    edge_walls(outer, signed_area(outer) > 0);
    for (const Ring& hole : holes) edge_walls(hole, signed_area(hole) < 0);
    return walls;
}

}  // namespace citygen
