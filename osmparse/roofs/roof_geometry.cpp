#include "osmparse/roofs/roof_geometry.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "osmparse/roofs/roof_skeleton.h"
#include "osmparse/roofs/wavefront_skeleton.h"

namespace citygen {

namespace {

// A footprint filling at least this share of its minimum-area rectangle takes ridge roofs over
// that rectangle; a more bent one is built hipped from its straight skeleton.
constexpr double kNearRectangle = 0.85;

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

// The parts of a simple counter-clockwise ring where g(p) <= 0. A non-convex ring may fall
// apart into several pieces: its inside chains are joined along the line g = 0, from each
// crossing where the ring leaves the half-plane to the next crossing along the line (walking
// the line with the inside on the left). False when the crossings do not pair up (degenerate).
bool clip_pieces(const Ring& ring, const Plane& g, std::vector<Ring>* pieces) {
    pieces->clear();
    const size_t n = ring.size();
    std::vector<double> value(n);
    bool any_in = false, any_out = false;
    for (size_t i = 0; i < n; ++i) {
        value[i] = g.at(ring[i]);
        (value[i] <= 0 ? any_in : any_out) = true;
    }
    if (!any_out) {
        pieces->push_back(ring);
        return true;
    }
    if (!any_in) return true;
    struct Node {
        Vec2 p;
        int crossing;  // -1 for a ring vertex, else +1 leaving the half-plane, 0 entering it
    };
    std::vector<Node> nodes;
    std::vector<size_t> crossings;
    for (size_t i = 0; i < n; ++i) {
        const size_t j = (i + 1) % n;
        const bool in_i = value[i] <= 0, in_j = value[j] <= 0;
        if (in_i) nodes.push_back({ring[i], -1});
        if (in_i != in_j) {
            const double t = value[i] / (value[i] - value[j]);
            crossings.push_back(nodes.size());
            nodes.push_back({ring[i] + (ring[j] - ring[i]) * t, in_i ? 1 : 0});
        }
    }
    const Vec2 along{-g.b, g.a};  // the inside (g < 0) is on its left
    std::sort(crossings.begin(), crossings.end(),
              [&](size_t x, size_t y) { return dot(nodes[x].p, along) < dot(nodes[y].p, along); });
    std::vector<size_t> next(nodes.size());
    for (size_t k = 0; k < nodes.size(); ++k) next[k] = (k + 1) % nodes.size();
    for (size_t k = 0; k < crossings.size(); ++k) {
        if (nodes[crossings[k]].crossing != 1) continue;
        if (k + 1 >= crossings.size() || nodes[crossings[k + 1]].crossing != 0) return false;
        next[crossings[k]] = crossings[k + 1];
    }
    std::vector<bool> used(nodes.size(), false);
    for (size_t start = 0; start < nodes.size(); ++start) {
        if (used[start]) continue;
        Ring piece;
        for (size_t k = start; !used[k]; k = next[k]) {
            used[k] = true;
            piece.push_back(nodes[k].p);
        }
        pieces->push_back(std::move(piece));
    }
    return true;
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
    face.points.reserve(ring.size());  // exactly: faces are kept to the end of the parse
    for (Vec2 p : ring) face.points.push_back({p.x, p.y, eaves_z + plane.at(p)});
    return face;
}

// The roof surface min over `planes` on a convex footprint: each plane's face is the footprint
// where that plane is the lowest.
// The roof surface min over `planes` on a footprint without holes: each plane's faces are the
// parts of the footprint where that plane is the lowest. False when a clip is degenerate.
bool lower_envelope(const Ring& outer, const std::vector<Plane>& planes, double eaves_z,
                    std::vector<RoofFace>* faces) {
    std::vector<Ring> pieces, clipped, next;
    for (size_t i = 0; i < planes.size(); ++i) {
        pieces = {outer};
        for (size_t j = 0; j < planes.size() && !pieces.empty(); ++j) {
            if (j == i) continue;
            const Plane diff{planes[i].a - planes[j].a, planes[i].b - planes[j].b, planes[i].c - planes[j].c};
            next.clear();
            for (const Ring& piece : pieces) {
                if (!clip_pieces(piece, diff, &clipped)) return false;
                next.insert(next.end(), clipped.begin(), clipped.end());
            }
            pieces.swap(next);
        }
        for (const Ring& piece : pieces) {
            const Ring clean = without_repeats(piece);
            if (clean.size() < 3 || signed_area(clean) < 1e-4) continue;
            faces->push_back(lift(clean, planes[i], eaves_z));
        }
    }
    return true;
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

// The straight skeleton's faces. On a convex footprint without holes the skeleton roof is the
// lower envelope of the planes rising from each edge at one slope, which the half-plane clipper
// builds several times faster than CGAL (whose exact predicates dominate the parse otherwise).
bool skeleton_faces(const Ring& outer, const std::vector<Ring>& holes, std::vector<SkeletonFace>* skeleton) {
    skeleton->clear();
    if (holes.empty() && ring_is_convex(outer)) {
        std::vector<Plane> planes;
        for (size_t i = 0, n = outer.size(); i < n; ++i) {
            const Vec2 a = outer[i], d = outer[(i + 1) % n] - a;
            const double len = length(d);
            if (!(len > 0)) continue;
            planes.push_back({-d.y / len, d.x / len, (d.y * a.x - d.x * a.y) / len});  // distance inside the edge
        }
        std::vector<RoofFace> faces;
        if (lower_envelope(outer, planes, 0, &faces) && !faces.empty()) {
            for (const RoofFace& f : faces) {
                SkeletonFace face;
                for (Vec3 p : f.points) {
                    face.points.push_back({p.x, p.y});
                    face.times.push_back(p.z < 1e-7 ? 0.0 : p.z);  // on the footprint
                }
                skeleton->push_back(std::move(face));
            }
            return true;
        }
        skeleton->clear();
    }
    // Bent footprints without holes: the wavefront in doubles, CGAL's exact predicates only
    // where that cannot decide (ties, parallel edges), as CGAL dominates the stage otherwise.
    if (holes.empty() && wavefront_skeleton_faces(outer, skeleton)) return true;
    return straight_skeleton_faces(outer, holes, skeleton);
}

// Skeleton nodes shared by faces: CGAL gives them bit-identical, the convex envelope nearly.
bool same_point(Vec2 p, Vec2 q) { return std::fabs(p.x - q.x) < 1e-6 && std::fabs(p.y - q.y) < 1e-6; }

// Gables on a skeleton roof (what Streets GL does): each end face that is a triangle (a footprint
// edge a-b rising to one skeleton node P shared with only the two neighbouring faces) is folded
// up into a vertical gable: P slides along the ridge the two neighbours' planes meet in, until
// it stands over a-b. The neighbours stay planar (P stays on both planes) and now cover the
// triangle; gable_walls() later builds the wall under the new roof edge. Returns the count.
int fold_gables(std::vector<SkeletonFace>& skeleton) {
    auto contour_edge = [](const SkeletonFace& f, Vec2* u, Vec2* v) {
        for (size_t i = 0, n = f.points.size(); i < n; ++i)
            if (f.times[i] == 0 && f.times[(i + 1) % n] == 0) {
                *u = f.points[i];
                *v = f.points[(i + 1) % n];
                return true;
            }
        return false;
    };
    // Distance inside a face's contour edge u->v (the face lies on its left).
    auto distance_to_line = [](Vec2 p, Vec2 u, Vec2 v) { return cross(v - u, p - u) / length(v - u); };
    int folded = 0;
    for (size_t k = 0; k < skeleton.size(); ++k) {
        SkeletonFace& end = skeleton[k];
        if (end.points.size() != 3) continue;
        size_t apex = 3;
        for (size_t i = 0; i < 3; ++i)
            if (end.times[i] > 0) apex = apex == 3 ? i : 4;
        if (apex >= 3) continue;
        const Vec2 node = end.points[apex];
        const Vec2 a = end.points[(apex + 1) % 3], b = end.points[(apex + 2) % 3];
        // The faces sharing the node: exactly the two neighbours beside a and b.
        std::vector<size_t> sharing;
        for (size_t j = 0; j < skeleton.size(); ++j)
            if (j != k)
                for (Vec2 p : skeleton[j].points)
                    if (same_point(p, node)) {
                        sharing.push_back(j);
                        break;
                    }
        if (sharing.size() != 2) continue;
        Vec2 au, av, bu, bv;
        int at_a = -1, at_b = -1;
        for (size_t j : sharing) {
            Vec2 u, v;
            if (!contour_edge(skeleton[j], &u, &v)) continue;
            if (same_point(u, a) || same_point(v, a)) at_a = static_cast<int>(j), au = u, av = v;
            if (same_point(u, b) || same_point(v, b)) at_b = static_cast<int>(j), bu = u, bv = v;
        }
        if (at_a < 0 || at_b < 0 || at_a == at_b) continue;
        // On a-b, the point as far from the neighbour's edge at a as from the one at b.
        const double da = distance_to_line(b, au, av), db = distance_to_line(a, bu, bv);
        if (!(da > 0) || !(db > 0)) continue;  // a neighbour's edge line crosses a-b: no simple gable
        const double lambda = db / (da + db);
        const Vec2 moved = a + (b - a) * lambda;
        const double time = distance_to_line(moved, au, av);
        if (!(time > 0)) continue;
        for (size_t j : sharing)
            for (size_t i = 0; i < skeleton[j].points.size(); ++i)
                if (same_point(skeleton[j].points[i], node)) {
                    skeleton[j].points[i] = moved;
                    skeleton[j].times[i] = time;
                }
        end.points.clear();  // now the gable wall, built with the walls
        end.times.clear();
        ++folded;
    }
    return folded;
}

// Hipped roof from the straight skeleton (height = offset time x slope), optionally with its
// end triangles folded into gables; `folded` (optional) receives how many were.
bool hipped(const Ring& outer, const std::vector<Ring>& holes, double eaves_z, double height,
            std::vector<RoofFace>* faces, ReportReason* why, bool gables = false, int* folded = nullptr) {
    std::vector<SkeletonFace> skeleton;
    if (!skeleton_faces(outer, holes, &skeleton)) {
        *why = ReportReason::RoofSkeletonFailed;
        return false;
    }
    double last = 0;
    for (const SkeletonFace& f : skeleton)
        for (double t : f.times) last = std::max(last, t);
    if (!(last > 1e-6) || !std::isfinite(last)) {
        *why = ReportReason::RoofSkeletonFailed;
        return false;
    }
    const int gable_count = gables ? fold_gables(skeleton) : 0;
    if (folded) *folded = gable_count;
    for (const SkeletonFace& f : skeleton)  // a folded ridge may rise above the last node
        for (double t : f.times) last = std::max(last, t);
    const double slope = height / last;
    for (const SkeletonFace& f : skeleton) {
        if (f.points.size() < 3) continue;
        RoofFace face;
        face.points.reserve(f.points.size());  // exactly: faces are kept to the end of the parse
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

// The profile (radius, height), both 0..1, of a roof of revolution.
std::vector<std::pair<double, double>> revolution_profile(RoofShape shape) {
    std::vector<std::pair<double, double>> profile;
    if (shape == RoofShape::Dome) {
        for (int k = 0; k <= 6; ++k) {
            const double a = 0.5 * kPi * k / 6;
            profile.push_back({k == 6 ? 0.0 : std::cos(a), std::sin(a)});
        }
    } else {  // onion: narrow neck, widest a quarter up, then an S curve to a point
        profile = {{1.0, 0.0},  {0.8, 0.0},  {0.92, 0.08}, {1.0, 0.2},  {0.95, 0.32}, {0.8, 0.45},
                   {0.55, 0.6}, {0.3, 0.75}, {0.12, 0.88}, {0.04, 0.95}, {0.0, 1.0}};
    }
    return profile;
}

// The planes of a ridge roof over the footprint's bounding rectangle; the roof is their lower
// envelope. Nothing for a shape that is not a ridge roof.
std::optional<std::vector<Plane>> ridge_roof_planes(const RoofFrame& f, RoofShape shape, double h) {
    std::vector<Plane> planes;
    switch (shape) {
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
        default: return std::nullopt;
    }
    return planes;
}

// Whether the faces tile the footprint: if a clip went wrong, no roof rather than a hole in it.
bool faces_tile(const std::vector<RoofFace>& faces, const Ring& outer) {
    double covered = 0;
    for (const RoofFace& face : faces) {
        Ring flat;
        for (Vec3 p : face.points) flat.push_back({p.x, p.y});
        covered += signed_area(flat);
    }
    return std::fabs(covered - signed_area(outer)) <= 1e-3 * std::fabs(signed_area(outer));
}

}  // namespace

bool split_off(const Ring& ring, Vec2 normal, double offset, std::vector<Ring>* pieces) {
    return clip_pieces(ring, Plane{normal.x, normal.y, -offset}, pieces);
}

bool face_is_planar(const RoofFace& face, double tolerance) {
    const std::vector<Vec3>& p = face.points;
    if (p.size() < 3) return false;
    const Vec3 n = normalize(newell_normal(p));
    if (!(length(n) > 0)) return false;
    for (Vec3 q : p)
        if (!(std::fabs(dot(n, q - p[0])) <= tolerance)) return false;
    return true;
}

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
                     std::vector<RoofFace>* faces, RoofShape* built, ReportReason* why) {
    faces->clear();
    *built = spec.shape;
    if (spec.shape == RoofShape::Flat) return true;
    if (outer.size() < 3 || !(spec.height > 0)) {
        *why = ReportReason::RoofDegenerateFootprint;
        return false;
    }
    const double z = spec.eaves_z, h = spec.height;
    const bool convex = holes.empty() && ring_is_convex(outer);
    const RoofFrame f = roof_frame(outer, spec);
    // Ridge roofs over the bounding rectangle suit footprints that nearly fill it.
    const bool near_rectangle =
        holes.empty() && std::fabs(signed_area(outer)) >= kNearRectangle * f.width() * f.length();
    if (!(f.width() > 0.1) || !(f.length() > 0.1)) {
        *why = ReportReason::RoofDegenerateFootprint;
        return false;
    }
    // Gables, ridges and curves across a bent or holed footprint: the skeleton's hipped roof
    // (what a courtyard block's wings look like anyway).
    auto as_hipped = [&] {
        faces->clear();
        *built = RoofShape::Hipped;
        return hipped(outer, holes, z, h, faces, why);
    };
    switch (spec.shape) {
        case RoofShape::Flat: return true;
        case RoofShape::Hipped: return hipped(outer, holes, z, h, faces, why);
        case RoofShape::Skillion: {
            if (!holes.empty()) return as_hipped();
            // With a direction the frame's across axis points uphill (roof_frame), so the top is
            // at t1; without one, the long side at t0 is the high one.
            const Plane plane = spec.has_direction ? across_plane(f, f.t0, 0, f.t1, h)
                                                   : across_plane(f, f.t0, h, f.t1, 0);
            faces->push_back(lift(outer, plane, z));
            return true;
        }
        case RoofShape::Pyramidal:
            if (!convex) return as_hipped();
            *faces = pyramid(outer, z, h);
            return true;
        case RoofShape::Dome:
        case RoofShape::Onion: {
            if (!convex) return as_hipped();
            *faces = revolution(outer, z, h, revolution_profile(spec.shape));
            return true;
        }
        default: break;
    }
    if (!near_rectangle && spec.shape == RoofShape::Gabled) {
        int folded = 0;
        if (!hipped(outer, holes, z, h, faces, why, true, &folded)) return false;
        bool planar = true;
        for (const RoofFace& face : *faces) planar = planar && face_is_planar(face, 1e-3);
        if (!planar) return as_hipped();  // a fold that tilted a face: keep the hips
        if (folded == 0) *built = RoofShape::Hipped;  // nothing to fold (a courtyard's ring of wings)
        return true;
    }
    if (!near_rectangle) return as_hipped();
    const std::optional<std::vector<Plane>> planes = ridge_roof_planes(f, spec.shape, h);
    if (!planes) {
        *why = ReportReason::RoofUnknownShape;
        return false;
    }
    if (!lower_envelope(outer, *planes, z, faces) || faces->empty() || !faces_tile(*faces, outer)) return as_hipped();
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
