#include "render/geometry/procedural_geometry.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>

#include "render/facade/wall_intersect.h"
#include "render/geometry/face_plane.h"

namespace citygen {

ProceduralGeometry::ProceduralGeometry(ObjectKind kind, const SurfaceMaterials& wall_materials)
    : kind_(kind), wall_materials_(wall_materials) {
    static std::atomic<uint64_t> instances{0};
    id_ = ++instances;  // never 0: an empty cache slot belongs to no instance
}

uint32_t ProceduralGeometry::add_facade_choices(const FacadeChoices& choices) { return choices_.push_back(choices); }

void ProceduralGeometry::add_wall(uint32_t object, const WallInput& wall, uint32_t choices, const WallGrid& grid,
                                  Vec2 a, Vec2 b, double bottom) {
    const uint32_t grid_index = grid.plain() ? kPlainWall : grids_.push_back(grid);
    walls_.push_back({{a.x, a.y, bottom}, normalize(b - a), wall.length, wall.height, object, wall.wall_index,
                      grid_index, choices});
}

void ProceduralGeometry::add_polygon(uint32_t object, const Ring& outer, const std::vector<Ring>& holes, double z,
                                     uint16_t material, int normal_z) {
    Polygon polygon;
    polygon.first_ring = static_cast<uint32_t>(ring_ends_.size());
    polygon.ring_count = static_cast<uint32_t>(1 + holes.size());
    polygon.z = z;
    polygon.bounds = bounds_of(outer);
    polygon.object = object;
    polygon.material = material;
    polygon.normal_z = static_cast<int8_t>(normal_z < 0 ? -1 : 1);
    points_.insert(points_.end(), outer.begin(), outer.end());
    ring_ends_.push_back(static_cast<uint32_t>(points_.size()));
    for (const Ring& hole : holes) {
        points_.insert(points_.end(), hole.begin(), hole.end());
        ring_ends_.push_back(static_cast<uint32_t>(points_.size()));
    }
    polygon.hole_root = kNoHoleTree;
    if (holes.size() > kHoleTreeMin) {
        // Median splits on the wider axis of the holes' box centres: O(h log h), depth log2(h).
        struct Item {
            Box2 box;
            Vec2 centre;
            uint32_t ring;
        };
        std::vector<Item> items(holes.size());
        for (size_t h = 0; h < holes.size(); ++h) {
            items[h].box = bounds_of(holes[h]);
            items[h].centre = (items[h].box.min + items[h].box.max) * 0.5;
            items[h].ring = polygon.first_ring + 1 + static_cast<uint32_t>(h);
        }
        polygon.hole_root = static_cast<uint32_t>(hole_nodes_.size());
        auto build = [&](auto&& self, size_t begin, size_t end) -> void {
            const size_t node = hole_nodes_.size();
            hole_nodes_.push_back({});
            Box2 box, centres;
            for (size_t i = begin; i < end; ++i) {
                box.extend(items[i].box.min);
                box.extend(items[i].box.max);
                centres.extend(items[i].centre);
            }
            hole_nodes_[node].box = box;
            if (end - begin <= kHoleLeafSize) {
                hole_nodes_[node].first = static_cast<uint32_t>(hole_rings_.size());
                hole_nodes_[node].count = static_cast<uint32_t>(end - begin);
                for (size_t i = begin; i < end; ++i) hole_rings_.push_back(items[i].ring);
                return;
            }
            const bool x = centres.max.x - centres.min.x >= centres.max.y - centres.min.y;
            const size_t mid = begin + (end - begin) / 2;
            std::nth_element(items.begin() + begin, items.begin() + mid, items.begin() + end,
                             [x](const Item& a, const Item& b) {
                                 const double ka = x ? a.centre.x : a.centre.y, kb = x ? b.centre.x : b.centre.y;
                                 return ka != kb ? ka < kb : a.ring < b.ring;
                             });
            self(self, begin, mid);
            hole_nodes_[node].first = static_cast<uint32_t>(hole_nodes_.size());
            hole_nodes_[node].count = 0;
            self(self, mid, end);
        };
        build(build, 0, items.size());
    }
    polygons_.push_back(polygon);
}

void ProceduralGeometry::add_curbed_polygon(uint32_t object, const Ring& outer, double z, uint16_t material,
                                            double curb_bottom) {
    add_polygon(object, outer, {}, z, material, +1);
    polygons_.back().curbed = true;
    polygons_.back().curb_bottom = curb_bottom;
}

void ProceduralGeometry::add_face(uint32_t object, const std::vector<Vec3>& points, uint16_t material) {
    FacePlane plane;
    if (!face_plane(points, &plane)) return;
    Face face;
    face.normal = plane.normal;
    face.axis_u = static_cast<uint8_t>(plane.axis_u);
    face.axis_v = static_cast<uint8_t>(plane.axis_v);
    face.offset = plane.offset;
    face.lo = {1e300, 1e300, 1e300};
    face.hi = {-1e300, -1e300, -1e300};
    face.first_point = static_cast<uint32_t>(face_points_.size());
    face.point_count = static_cast<uint32_t>(points.size());
    for (Vec3 p : points) {
        face.lo = {std::min(face.lo.x, p.x), std::min(face.lo.y, p.y), std::min(face.lo.z, p.z)};
        face.hi = {std::max(face.hi.x, p.x), std::max(face.hi.y, p.y), std::max(face.hi.z, p.z)};
        face_points_.push_back({p[face.axis_u], p[face.axis_v]});
    }
    face.object = object;
    face.material = material;
    faces_.push_back(face);
}

void ProceduralGeometry::append(const ProceduralGeometry& part) {
    const uint32_t grids = grids_.size(), choices = choices_.size();
    const auto rings = static_cast<uint32_t>(ring_ends_.size()), points = static_cast<uint32_t>(points_.size());
    const auto hole_nodes = static_cast<uint32_t>(hole_nodes_.size());
    const auto hole_rings = static_cast<uint32_t>(hole_rings_.size());
    const auto face_points = static_cast<uint32_t>(face_points_.size());
    for (uint32_t i = 0; i < part.choices_.size(); ++i) choices_.push_back(part.choices_[i]);
    for (uint32_t i = 0; i < part.grids_.size(); ++i) grids_.push_back(part.grids_[i]);
    for (Wall wall : part.walls_) {
        if (wall.grid != kPlainWall) {
            wall.grid += grids;
            wall.choices += choices;
        }
        walls_.push_back(wall);
    }
    for (Polygon polygon : part.polygons_) {
        polygon.first_ring += rings;
        if (polygon.hole_root != kNoHoleTree) polygon.hole_root += hole_nodes;
        polygons_.push_back(polygon);
    }
    for (uint32_t end : part.ring_ends_) ring_ends_.push_back(end + points);
    points_.insert(points_.end(), part.points_.begin(), part.points_.end());
    for (HoleNode node : part.hole_nodes_) {
        node.first += node.count > 0 ? hole_rings : hole_nodes;  // a leaf's rings, or an inner node's second child
        hole_nodes_.push_back(node);
    }
    for (uint32_t ring : part.hole_rings_) hole_rings_.push_back(ring + rings);
    for (Face face : part.faces_) {
        face.first_point += face_points;
        faces_.push_back(face);
    }
    face_points_.insert(face_points_.end(), part.face_points_.begin(), part.face_points_.end());
}

size_t ProceduralGeometry::buffer_bytes() const {
    return walls_.capacity() * sizeof(Wall) + wall_runs_.capacity() * sizeof(uint32_t) + grids_.bytes() +
           choices_.bytes() +
           faces_.capacity() * sizeof(Face) + face_points_.capacity() * sizeof(Vec2) +
           polygons_.capacity() * sizeof(Polygon) +
           points_.capacity() * sizeof(Vec2) + ring_ends_.capacity() * sizeof(uint32_t) +
           hole_nodes_.capacity() * sizeof(HoleNode) + hole_rings_.capacity() * sizeof(uint32_t);
}

bool ProceduralGeometry::in_ring(uint32_t ring, Vec2 p) const {
    const uint32_t begin = ring == 0 ? 0 : ring_ends_[ring - 1];
    return point_in_ring(p, points_.data() + begin, ring_ends_[ring] - begin);
}

namespace {
bool box_holds(const Box2& b, Vec2 p) { return p.x >= b.min.x && p.x <= b.max.x && p.y >= b.min.y && p.y <= b.max.y; }
}  // namespace

bool ProceduralGeometry::in_some_hole(uint32_t root, Vec2 p) const {
    // A point outside a ring's bounding box has winding number 0: skipping such holes changes
    // nothing. The tree is balanced, so 64 entries hold any path.
    uint32_t stack[64];
    int top = 0;
    stack[top++] = root;
    while (top > 0) {
        const HoleNode& node = hole_nodes_[stack[--top]];
        if (!box_holds(node.box, p)) continue;
        if (node.count > 0) {
            for (uint32_t i = node.first; i < node.first + node.count; ++i)
                if (in_ring(hole_rings_[i], p)) return true;
            continue;
        }
        stack[top++] = node.first;
        stack[top++] = static_cast<uint32_t>(&node - hole_nodes_.data()) + 1;
    }
    return false;
}

bool ProceduralGeometry::inside_polygon(const Polygon& polygon, Vec2 p) const {
    if (!box_holds(polygon.bounds, p)) return false;
    if (polygon.hole_root != kNoHoleTree)
        return in_ring(polygon.first_ring, p) && !in_some_hole(polygon.hole_root, p);
    for (uint32_t r = 0; r < polygon.ring_count; ++r) {
        const bool inside = in_ring(polygon.first_ring + r, p);
        if (inside != (r == 0)) return false;  // outside the outer ring, or inside a hole
    }
    return true;
}

bool ProceduralGeometry::intersect_face(const Face& face, Vec3 origin, Vec3 direction, double tmin, double tmax,
                                        double* t) const {
    const double denom = dot(face.normal, direction);
    if (denom == 0) return false;
    const double hit_t = (face.offset - dot(face.normal, origin)) / denom;
    if (!(hit_t >= tmin && hit_t <= tmax)) return false;
    const Vec3 p = origin + direction * hit_t;
    if (!point_in_ring({p[face.axis_u], p[face.axis_v]}, face_points_.data() + face.first_point, face.point_count))
        return false;
    *t = hit_t;
    return true;
}

bool ProceduralGeometry::intersect_surface(uint32_t prim_id, Vec3 origin, Vec3 direction, double tmin, double tmax,
                                           PrimitiveHit* hit) const {
    if (prim_id < walls_.size()) {
        WallHit wall_hit;
        const bool hit_wall = with_wall(prim_id, [&](const WallLayout& layout, const WallFrame& frame) {
            return intersect_wall(layout, frame, origin, direction, tmin, tmax, &wall_hit);
        });
        if (!hit_wall) return false;
        hit->t = wall_hit.t;
        hit->normal = wall_hit.normal;
        hit->material = wall_materials_[static_cast<int>(wall_hit.surface)];
        hit->cell = wall_hit.floor < 0 ? 0 : static_cast<uint32_t>(wall_hit.floor) * 65536u + wall_hit.slot + 1;
        return true;
    }
    const size_t polygon_index = prim_id - walls_.size();
    if (polygon_index >= polygons_.size()) {
        const Face& face = faces_[polygon_index - polygons_.size()];
        double t;
        if (!intersect_face(face, origin, direction, tmin, tmax, &t)) return false;
        hit->t = t;
        hit->normal = face.normal;
        hit->material = face.material;
        hit->cell = 0;
        return true;
    }
    const Polygon& polygon = polygons_[polygon_index];
    bool found = false;
    if (direction.z != 0) {
        const double t = (polygon.z - origin.z) / direction.z;
        if (t >= tmin && t <= tmax && inside_polygon(polygon, {origin.x + direction.x * t, origin.y + direction.y * t})) {
            hit->t = t;
            hit->normal = {0, 0, double(polygon.normal_z)};
            hit->material = polygon.material;
            hit->cell = 0;
            found = true;
        }
    }
    PrimitiveHit curb_hit;
    if (polygon.curbed && intersect_curbs(polygon, origin, direction, tmin, found ? hit->t : tmax, &curb_hit) &&
        (!found || curb_hit.t < hit->t)) {
        *hit = curb_hit;
        found = true;
    }
    return found;
}

bool ProceduralGeometry::intersect_curbs(const Polygon& polygon, Vec3 origin, Vec3 direction, double tmin, double tmax,
                                         PrimitiveHit* hit) const {
    // Each edge a plain wall (as a building wall too small for windows), from a at the curb's foot.
    const uint32_t begin = polygon.first_ring == 0 ? 0 : ring_ends_[polygon.first_ring - 1];
    const uint32_t n = ring_ends_[polygon.first_ring] - begin;
    const Vec2* ring = points_.data() + begin;
    bool found = false;
    for (uint32_t k = 0; k < n; ++k) {
        const Vec2 a = ring[k], b = ring[(k + 1) % n];
        if (a == b) continue;
        WallLayout curb;
        curb.length = length(b - a);
        curb.height = polygon.z - polygon.curb_bottom;
        WallHit wall_hit;
        const WallFrame frame = wall_frame(Vec3{a.x, a.y, polygon.curb_bottom}, normalize(b - a));
        if (!intersect_wall(curb, frame, origin, direction, tmin, tmax, &wall_hit) || (found && !(wall_hit.t < tmax)))
            continue;
        tmax = wall_hit.t;
        hit->t = wall_hit.t;
        hit->normal = wall_hit.normal;
        hit->material = wall_materials_[static_cast<int>(wall_hit.surface)];
        hit->cell = 0;
        found = true;
    }
    return found;
}

bool ProceduralGeometry::surface_occluded(uint32_t prim_id, Vec3 origin, Vec3 direction, double tmin,
                                          double tmax) const {
    if (prim_id < walls_.size()) {
        return with_wall(prim_id, [&](const WallLayout& layout, const WallFrame& frame) {
            return wall_occluded(layout, frame, origin, direction, tmin, tmax);
        });
    }
    PrimitiveHit hit;
    return intersect_surface(prim_id, origin, direction, tmin, tmax, &hit);
}

void ProceduralGeometry::surface_bounds(uint32_t prim_id, Vec3* lo_out, Vec3* hi_out) const {
    Vec3& lo = *lo_out;
    Vec3& hi = *hi_out;
    auto extend = [&](Vec3 p) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    };
    if (prim_id < walls_.size()) {
        with_wall(prim_id, [&](const WallLayout& layout, const WallFrame& frame) {
            for (double u : {0.0, layout.length})
                for (double v : {0.0, layout.height})
                    for (double w : {layout.w_min(), layout.w_max()}) extend(frame.to_world(u, v, w));
        });
    } else if (prim_id >= walls_.size() + polygons_.size()) {
        const Face& face = faces_[prim_id - walls_.size() - polygons_.size()];
        extend(face.lo);
        extend(face.hi);
    } else {
        const Polygon& polygon = polygons_[prim_id - walls_.size()];
        extend({polygon.bounds.min.x, polygon.bounds.min.y, polygon.curbed ? polygon.curb_bottom : polygon.z});
        extend({polygon.bounds.max.x, polygon.bounds.max.y, polygon.z});
    }
}

uint32_t ProceduralGeometry::first_surface(unsigned prim_id, uint32_t* count) const {
    const size_t runs = wall_runs_.size() - 1;
    if (prim_id < runs) {
        *count = wall_runs_[prim_id + 1] - wall_runs_[prim_id];
        return wall_runs_[prim_id];
    }
    *count = 1;
    return static_cast<uint32_t>(prim_id - runs + walls_.size());
}

void ProceduralGeometry::bounds(unsigned prim_id, RTCBounds* out) const {
    Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    uint32_t count;
    const uint32_t first = first_surface(prim_id, &count);
    for (uint32_t s = first; s < first + count; ++s) surface_bounds(s, &lo, &hi);
    // Pad so that float rounding of the bounds never cuts off a surface on their faces.
    const double pad = 1e-3;
    set_bounds(out, {lo.x - pad, lo.y - pad, lo.z - pad}, {hi.x + pad, hi.y + pad, hi.z + pad});
}

bool ProceduralGeometry::intersect(unsigned prim_id, Vec3 origin, Vec3 direction, double tmin, double tmax,
                                   PrimitiveHit* hit) const {
    uint32_t count;
    const uint32_t first = first_surface(prim_id, &count);
    // The nearest as Embree would keep it with each surface alone: in float, a tie to the lower id.
    bool found = false;
    float nearest = 0;
    for (uint32_t s = first; s < first + count; ++s) {
        PrimitiveHit h;
        if (!intersect_surface(s, origin, direction, tmin, tmax, &h)) continue;
        const float t = static_cast<float>(h.t);
        if (found && !(t < nearest)) continue;
        *hit = h;
        hit->primitive = s;
        nearest = t;
        tmax = std::nextafter(t, std::numeric_limits<float>::infinity());
        found = true;
    }
    return found;
}

bool ProceduralGeometry::occluded(unsigned prim_id, Vec3 origin, Vec3 direction, double tmin, double tmax) const {
    uint32_t count;
    const uint32_t first = first_surface(prim_id, &count);
    for (uint32_t s = first; s < first + count; ++s)
        if (surface_occluded(s, origin, direction, tmin, tmax)) return true;
    return false;
}

RTCGeometry ProceduralGeometry::create_embree_geometry(RTCDevice device) {
    // Runs of up to kWallsPerRun walls of one object, in order.
    wall_runs_.clear();
    for (uint32_t w = 0; w < walls_.size(); ++w)
        if (wall_runs_.empty() || w - wall_runs_.back() == kWallsPerRun ||
            walls_[w].object != walls_[wall_runs_.back()].object)
            wall_runs_.push_back(w);
    wall_runs_.push_back(static_cast<uint32_t>(walls_.size()));
    wall_runs_.shrink_to_fit();
    // Building is over: give back what the vectors grew into (up to half their bytes).
    walls_.shrink_to_fit();
    polygons_.shrink_to_fit();
    faces_.shrink_to_fit();
    face_points_.shrink_to_fit();
    points_.shrink_to_fit();
    ring_ends_.shrink_to_fit();
    return new_user_geometry(device, this, wall_runs_.size() - 1 + polygons_.size() + faces_.size());
}

void ProceduralGeometry::complete_hit(const RTCHit& embree_hit, Hit& hit) const {
    complete_user_hit(embree_hit, kind_, object(embree_hit.primID), hit);
    if (embree_hit.primID < walls_.size()) {
        hit.wall = walls_[embree_hit.primID].wall_index;
        hit.cell = static_cast<uint32_t>(embree_hit.v);
    }
}

}  // namespace citygen
