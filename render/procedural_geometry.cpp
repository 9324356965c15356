#include "procedural_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "wall_intersect.h"

namespace citygen {

void ProceduralGeometry::add_wall(uint32_t object, const WallLayout& layout, const WallFrame& frame,
                                  uint32_t wall_index) {
    walls_.push_back({layout, frame, object, wall_index});
}

void ProceduralGeometry::add_plain_wall(uint32_t object, Vec2 a, Vec2 b, double bottom, double height) {
    plain_walls_.push_back({{a.x, a.y, bottom}, normalize(b - a), length(b - a), height, object});
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
    polygons_.push_back(polygon);
}

void ProceduralGeometry::add_face(uint32_t object, const std::vector<Vec3>& points, uint16_t material) {
    if (points.size() < 3) return;
    // Newell's normal: robust for any planar polygon, its sign gives the front (CCW) side.
    Vec3 n{0, 0, 0};
    for (size_t i = 0; i < points.size(); ++i) {
        const Vec3 a = points[i] - points[0], b = points[(i + 1) % points.size()] - points[0];
        n = n + Vec3{(a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y)};
    }
    if (!(length(n) > 0)) return;
    Face face;
    face.normal = normalize(n);
    const Vec3 m{std::fabs(face.normal.x), std::fabs(face.normal.y), std::fabs(face.normal.z)};
    const int drop = m.z >= m.x && m.z >= m.y ? 2 : (m.y >= m.x ? 1 : 0);
    face.axis_u = static_cast<uint8_t>(drop == 0 ? 1 : 0);
    face.axis_v = static_cast<uint8_t>(drop == 2 ? 1 : 2);
    face.offset = 0;
    for (Vec3 p : points) face.offset += dot(face.normal, p);
    face.offset /= static_cast<double>(points.size());
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

size_t ProceduralGeometry::buffer_bytes() const {
    return walls_.capacity() * sizeof(Wall) + plain_walls_.capacity() * sizeof(PlainWall) +
           faces_.capacity() * sizeof(Face) + face_points_.capacity() * sizeof(Vec2) +
           polygons_.capacity() * sizeof(Polygon) +
           points_.capacity() * sizeof(Vec2) + ring_ends_.capacity() * sizeof(uint32_t);
}

namespace {

// Winding-number test over one ring stored in a span of points.
bool point_in_span(Vec2 p, const Vec2* ring, uint32_t n) {
    int winding = 0;
    for (uint32_t i = 0; i < n; ++i) {
        Vec2 a = ring[i], b = ring[i + 1 == n ? 0 : i + 1];
        if (a.y <= p.y) {
            if (b.y > p.y && cross(b - a, p - a) > 0) ++winding;
        } else if (b.y <= p.y && cross(b - a, p - a) < 0) {
            --winding;
        }
    }
    return winding != 0;
}

}  // namespace

bool ProceduralGeometry::inside_polygon(const Polygon& polygon, Vec2 p) const {
    const Box2& b = polygon.bounds;
    if (p.x < b.min.x || p.x > b.max.x || p.y < b.min.y || p.y > b.max.y) return false;
    for (uint32_t r = 0; r < polygon.ring_count; ++r) {
        const uint32_t ring = polygon.first_ring + r;
        const uint32_t begin = ring == 0 ? 0 : ring_ends_[ring - 1];
        const bool inside = point_in_span(p, points_.data() + begin, ring_ends_[ring] - begin);
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
    if (!point_in_span({p[face.axis_u], p[face.axis_v]}, face_points_.data() + face.first_point, face.point_count))
        return false;
    *t = hit_t;
    return true;
}

bool ProceduralGeometry::wall_of(unsigned prim_id, WallLayout* layout, WallFrame* frame) const {
    if (prim_id < walls_.size()) {
        *layout = walls_[prim_id].layout;
        *frame = walls_[prim_id].frame;
        return true;
    }
    prim_id -= static_cast<unsigned>(walls_.size());
    if (prim_id >= plain_walls_.size()) return false;
    const PlainWall& plain = plain_walls_[prim_id];
    layout->length = plain.length;
    layout->height = plain.height;
    frame->origin = plain.origin;
    frame->u_axis = {plain.along.x, plain.along.y, 0};
    frame->v_axis = {0, 0, 1};
    frame->w_axis = {-plain.along.y, plain.along.x, 0};
    return true;
}

bool ProceduralGeometry::intersect(unsigned prim_id, Vec3 origin, Vec3 direction, double tmin, double tmax,
                                   PrimitiveHit* hit) const {
    if (prim_id < walls_.size()) {  // the common case: no copy of the layout
        const Wall& wall = walls_[prim_id];
        WallHit wall_hit;
        if (!intersect_wall(wall.layout, wall.frame, origin, direction, tmin, tmax, &wall_hit)) return false;
        hit->t = wall_hit.t;
        hit->normal = wall_hit.normal;
        hit->material = wall_materials_[static_cast<int>(wall_hit.surface)];
        hit->cell = wall_hit.floor < 0 ? 0 : static_cast<uint32_t>(wall_hit.floor) * 65536u + wall_hit.slot + 1;
        return true;
    }
    WallLayout layout;
    WallFrame frame;
    if (wall_of(prim_id, &layout, &frame)) {
        WallHit wall_hit;
        if (!intersect_wall(layout, frame, origin, direction, tmin, tmax, &wall_hit)) return false;
        hit->t = wall_hit.t;
        hit->normal = wall_hit.normal;
        hit->material = wall_materials_[static_cast<int>(wall_hit.surface)];
        hit->cell = 0;
        return true;
    }
    const size_t polygon_index = prim_id - walls_.size() - plain_walls_.size();
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
    if (direction.z == 0) return false;
    const double t = (polygon.z - origin.z) / direction.z;
    if (!(t >= tmin && t <= tmax)) return false;
    if (!inside_polygon(polygon, {origin.x + direction.x * t, origin.y + direction.y * t})) return false;
    hit->t = t;
    hit->normal = {0, 0, double(polygon.normal_z)};
    hit->material = polygon.material;
    hit->cell = 0;
    return true;
}

bool ProceduralGeometry::occluded(unsigned prim_id, Vec3 origin, Vec3 direction, double tmin, double tmax) const {
    if (prim_id < walls_.size()) {
        const Wall& wall = walls_[prim_id];
        return wall_occluded(wall.layout, wall.frame, origin, direction, tmin, tmax);
    }
    WallLayout layout;
    WallFrame frame;
    if (wall_of(prim_id, &layout, &frame)) return wall_occluded(layout, frame, origin, direction, tmin, tmax);
    PrimitiveHit hit;
    return intersect(prim_id, origin, direction, tmin, tmax, &hit);
}

void ProceduralGeometry::bounds_callback(const RTCBoundsFunctionArguments* args) {
    const auto* self = static_cast<const ProceduralGeometry*>(args->geometryUserPtr);
    Vec3 lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    auto extend = [&](Vec3 p) {
        lo = {std::min(lo.x, p.x), std::min(lo.y, p.y), std::min(lo.z, p.z)};
        hi = {std::max(hi.x, p.x), std::max(hi.y, p.y), std::max(hi.z, p.z)};
    };
    WallLayout layout;
    WallFrame frame;
    if (self->wall_of(args->primID, &layout, &frame)) {
        for (double u : {0.0, layout.length})
            for (double v : {0.0, layout.height})
                for (double w : {layout.w_min(), layout.w_max()}) extend(frame.to_world(u, v, w));
    } else if (args->primID >= self->walls_.size() + self->plain_walls_.size() + self->polygons_.size()) {
        const Face& face =
            self->faces_[args->primID - self->walls_.size() - self->plain_walls_.size() - self->polygons_.size()];
        extend(face.lo);
        extend(face.hi);
    } else {
        const Polygon& polygon = self->polygons_[args->primID - self->walls_.size() - self->plain_walls_.size()];
        extend({polygon.bounds.min.x, polygon.bounds.min.y, polygon.z});
        extend({polygon.bounds.max.x, polygon.bounds.max.y, polygon.z});
    }
    // Pad so that float rounding of the bounds never cuts off a surface on their faces.
    const double pad = 1e-3;
    RTCBounds* b = args->bounds_o;
    b->lower_x = static_cast<float>(lo.x - pad);
    b->lower_y = static_cast<float>(lo.y - pad);
    b->lower_z = static_cast<float>(lo.z - pad);
    b->upper_x = static_cast<float>(hi.x + pad);
    b->upper_y = static_cast<float>(hi.y + pad);
    b->upper_z = static_cast<float>(hi.z + pad);
}

void ProceduralGeometry::intersect_callback(const RTCIntersectFunctionNArguments* args) {
    const auto* self = static_cast<const ProceduralGeometry*>(args->geometryUserPtr);
    RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
    RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, args->N);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const unsigned N = args->N;
        const Vec3 origin{RTCRayN_org_x(ray, N, i), RTCRayN_org_y(ray, N, i), RTCRayN_org_z(ray, N, i)};
        const Vec3 direction{RTCRayN_dir_x(ray, N, i), RTCRayN_dir_y(ray, N, i), RTCRayN_dir_z(ray, N, i)};
        PrimitiveHit found;
        if (!self->intersect(args->primID, origin, direction, RTCRayN_tnear(ray, N, i), RTCRayN_tfar(ray, N, i),
                             &found))
            continue;
        RTCRayN_tfar(ray, N, i) = static_cast<float>(found.t);
        RTCHitN_Ng_x(hit, N, i) = static_cast<float>(found.normal.x);
        RTCHitN_Ng_y(hit, N, i) = static_cast<float>(found.normal.y);
        RTCHitN_Ng_z(hit, N, i) = static_cast<float>(found.normal.z);
        RTCHitN_u(hit, N, i) = static_cast<float>(found.material);
        RTCHitN_v(hit, N, i) = static_cast<float>(found.cell);
        RTCHitN_primID(hit, N, i) = args->primID;
        RTCHitN_geomID(hit, N, i) = args->geomID;
        RTCHitN_instID(hit, N, i, 0) = args->context->instID[0];
    }
}

void ProceduralGeometry::occluded_callback(const RTCOccludedFunctionNArguments* args) {
    const auto* self = static_cast<const ProceduralGeometry*>(args->geometryUserPtr);
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const unsigned N = args->N;
        const Vec3 origin{RTCRayN_org_x(args->ray, N, i), RTCRayN_org_y(args->ray, N, i),
                          RTCRayN_org_z(args->ray, N, i)};
        const Vec3 direction{RTCRayN_dir_x(args->ray, N, i), RTCRayN_dir_y(args->ray, N, i),
                             RTCRayN_dir_z(args->ray, N, i)};
        if (self->occluded(args->primID, origin, direction, RTCRayN_tnear(args->ray, N, i),
                           RTCRayN_tfar(args->ray, N, i)))
            RTCRayN_tfar(args->ray, N, i) = -std::numeric_limits<float>::infinity();
    }
}

RTCGeometry ProceduralGeometry::create_embree_geometry(RTCDevice device) {
    // Building is over: give back what the vectors grew into (up to half their bytes).
    walls_.shrink_to_fit();
    plain_walls_.shrink_to_fit();
    polygons_.shrink_to_fit();
    faces_.shrink_to_fit();
    face_points_.shrink_to_fit();
    points_.shrink_to_fit();
    ring_ends_.shrink_to_fit();
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(geometry, static_cast<unsigned>(primitive_count()));
    rtcSetGeometryUserData(geometry, this);
    rtcSetGeometryBoundsFunction(geometry, bounds_callback, nullptr);
    rtcSetGeometryIntersectFunction(geometry, intersect_callback);
    rtcSetGeometryOccludedFunction(geometry, occluded_callback);
    return geometry;
}

void ProceduralGeometry::complete_hit(const RTCHit& embree_hit, Hit& hit) const {
    hit.kind = kind_;
    hit.object = object(embree_hit.primID);
    hit.material = static_cast<uint16_t>(embree_hit.u);
    if (embree_hit.primID < walls_.size()) {
        hit.wall = walls_[embree_hit.primID].wall_index;
        hit.cell = static_cast<uint32_t>(embree_hit.v);
    }
    hit.geometric_normal = normalize(Vec3{embree_hit.Ng_x, embree_hit.Ng_y, embree_hit.Ng_z});
    hit.shading_normal = hit.geometric_normal;
}

}  // namespace citygen
