// The Embree user-geometry callbacks every procedural class shares (buildings, roads and flat
// polygons, trees, lamps): the loops over a packet of rays and the hit they report. A class
// gives per primitive, in double precision:
//   void bounds(unsigned prim, RTCBounds* out) const;
//   bool intersect(unsigned prim, Vec3 origin, Vec3 direction, double tmin, double tmax, UserHit* hit) const;
//   bool occluded(unsigned prim, Vec3 origin, Vec3 direction, double tmin, double tmax) const;
// and new_user_geometry(device, this, count) makes the Embree geometry that calls them.
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>

#include <embree3/rtcore.h>

#include "common/geometry.h"
#include "render/scene/hit.h"

namespace citygen {

// What a primitive's intersection reports: Embree keeps t, the normal, and the material and
// facade cell in the hit's u and v.
struct UserHit {
    double t = 0;
    Vec3 normal;
    uint16_t material = 0;
    uint32_t cell = 0;
    // The primitive id the hit reports, when not Embree's own: a primitive that gathers several
    // surfaces (a run of walls) names the one hit, so ties and hits read as if each were alone.
    static constexpr uint32_t kEmbreePrimitive = 0xffffffffu;
    uint32_t primitive = kEmbreePrimitive;
};

// A primitive's box, from double-precision corners (callers pad them for float rounding).
inline void set_bounds(RTCBounds* out, Vec3 lo, Vec3 hi) {
    out->lower_x = static_cast<float>(lo.x);
    out->lower_y = static_cast<float>(lo.y);
    out->lower_z = static_cast<float>(lo.z);
    out->upper_x = static_cast<float>(hi.x);
    out->upper_y = static_cast<float>(hi.y);
    out->upper_z = static_cast<float>(hi.z);
}

namespace user_geometry {

template <typename Geometry>
void bounds(const RTCBoundsFunctionArguments* args) {
    static_cast<const Geometry*>(args->geometryUserPtr)->bounds(args->primID, args->bounds_o);
}

template <typename Geometry>
void intersect(const RTCIntersectFunctionNArguments* args) {
    const auto* self = static_cast<const Geometry*>(args->geometryUserPtr);
    RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
    RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, args->N);
    const unsigned N = args->N;
    for (unsigned i = 0; i < N; ++i) {
        if (args->valid[i] != -1) continue;
        const Vec3 origin{RTCRayN_org_x(ray, N, i), RTCRayN_org_y(ray, N, i), RTCRayN_org_z(ray, N, i)};
        const Vec3 direction{RTCRayN_dir_x(ray, N, i), RTCRayN_dir_y(ray, N, i), RTCRayN_dir_z(ray, N, i)};
        // At the same distance as the hit so far (coplanar overlapping surfaces: two road quads,
        // two sidewalk pieces), the lower (geometry, primitive) wins, so that the winner does
        // not depend on the order the BVH visits them in. The distance is compared as Embree
        // keeps it, in float: the search reaches a float step beyond tfar, or a tie whose double
        // distance lies just above its rounded tfar would never be seen.
        const float tfar = RTCRayN_tfar(ray, N, i);
        UserHit found;
        if (!self->intersect(args->primID, origin, direction, RTCRayN_tnear(ray, N, i),
                             std::nextafter(tfar, std::numeric_limits<float>::infinity()), &found))
            continue;
        const float t = static_cast<float>(found.t);
        if (t > tfar) continue;
        const unsigned prim = found.primitive == UserHit::kEmbreePrimitive ? args->primID : found.primitive;
        const unsigned held = RTCHitN_geomID(hit, N, i);
        if (t == tfar && held != RTC_INVALID_GEOMETRY_ID &&
            (held < args->geomID || (held == args->geomID && RTCHitN_primID(hit, N, i) < prim)))
            continue;
        RTCRayN_tfar(ray, N, i) = t;
        RTCHitN_Ng_x(hit, N, i) = static_cast<float>(found.normal.x);
        RTCHitN_Ng_y(hit, N, i) = static_cast<float>(found.normal.y);
        RTCHitN_Ng_z(hit, N, i) = static_cast<float>(found.normal.z);
        RTCHitN_u(hit, N, i) = static_cast<float>(found.material);
        RTCHitN_v(hit, N, i) = static_cast<float>(found.cell);
        RTCHitN_primID(hit, N, i) = prim;
        RTCHitN_geomID(hit, N, i) = args->geomID;
        RTCHitN_instID(hit, N, i, 0) = args->context->instID[0];
    }
}

template <typename Geometry>
void occluded(const RTCOccludedFunctionNArguments* args) {
    const auto* self = static_cast<const Geometry*>(args->geometryUserPtr);
    RTCRayN* ray = args->ray;
    const unsigned N = args->N;
    for (unsigned i = 0; i < N; ++i) {
        if (args->valid[i] != -1) continue;
        const Vec3 origin{RTCRayN_org_x(ray, N, i), RTCRayN_org_y(ray, N, i), RTCRayN_org_z(ray, N, i)};
        const Vec3 direction{RTCRayN_dir_x(ray, N, i), RTCRayN_dir_y(ray, N, i), RTCRayN_dir_z(ray, N, i)};
        if (self->occluded(args->primID, origin, direction, RTCRayN_tnear(ray, N, i), RTCRayN_tfar(ray, N, i)))
            RTCRayN_tfar(ray, N, i) = -std::numeric_limits<float>::infinity();
    }
}

}  // namespace user_geometry

template <typename Geometry>
RTCGeometry new_user_geometry(RTCDevice device, const Geometry* self, size_t primitive_count) {
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(geometry, static_cast<unsigned>(primitive_count));
    rtcSetGeometryUserData(geometry, const_cast<Geometry*>(self));
    rtcSetGeometryBoundsFunction(geometry, user_geometry::bounds<Geometry>, nullptr);
    rtcSetGeometryIntersectFunction(geometry, user_geometry::intersect<Geometry>);
    rtcSetGeometryOccludedFunction(geometry, user_geometry::occluded<Geometry>);
    return geometry;
}

// The hit fields every user geometry fills the same way: kind, object, material (from u),
// and the normal Embree kept.
inline void complete_user_hit(const RTCHit& embree_hit, ObjectKind kind, uint32_t object, Hit& hit) {
    hit.kind = kind;
    hit.object = object;
    hit.material = static_cast<uint16_t>(embree_hit.u);
    hit.geometric_normal = normalize(Vec3{embree_hit.Ng_x, embree_hit.Ng_y, embree_hit.Ng_z});
    hit.shading_normal = hit.geometric_normal;
}

}  // namespace citygen
