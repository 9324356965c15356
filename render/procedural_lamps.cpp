#include "procedural_lamps.h"

#include <limits>

#include "materials.h"

namespace citygen {

namespace {

uint16_t material_of(LampPart part) {
    switch (part) {
        case LampPart::Pole: return kLampPole;
        case LampPart::Globe: return kLampGlobe;
        case LampPart::Cap: return kLampCap;
    }
    return kLampPole;
}

}  // namespace

std::unique_ptr<ProceduralLamps> build_procedural_lamps(const Scene& scene) {
    auto geometry = std::make_unique<ProceduralLamps>();
    for (const Lamp& lamp : scene.lamps) geometry->add(lamp_shape(lamp, scene.ground.z));
    return geometry;
}

void ProceduralLamps::bounds_callback(const RTCBoundsFunctionArguments* args) {
    const auto* self = static_cast<const ProceduralLamps*>(args->geometryUserPtr);
    const LampShape& s = self->lamps_[args->primID];
    const double r = s.outer_radius() + 1e-3, pad = 1e-3;
    RTCBounds* b = args->bounds_o;
    b->lower_x = static_cast<float>(s.base.x - r);
    b->lower_y = static_cast<float>(s.base.y - r);
    b->lower_z = static_cast<float>(s.base.z - pad);
    b->upper_x = static_cast<float>(s.base.x + r);
    b->upper_y = static_cast<float>(s.base.y + r);
    b->upper_z = static_cast<float>(s.top() + pad);
}

void ProceduralLamps::intersect_callback(const RTCIntersectFunctionNArguments* args) {
    const auto* self = static_cast<const ProceduralLamps*>(args->geometryUserPtr);
    RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
    RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, args->N);
    const unsigned N = args->N;
    for (unsigned i = 0; i < N; ++i) {
        if (args->valid[i] != -1) continue;
        const Vec3 origin{RTCRayN_org_x(ray, N, i), RTCRayN_org_y(ray, N, i), RTCRayN_org_z(ray, N, i)};
        const Vec3 d{RTCRayN_dir_x(ray, N, i), RTCRayN_dir_y(ray, N, i), RTCRayN_dir_z(ray, N, i)};
        // The shape works with unit directions; t scales back by the direction's length.
        const double len = length(d);
        LampHit found;
        if (!intersect_lamp(self->lamps_[args->primID], origin, d * (1 / len), RTCRayN_tnear(ray, N, i) * len,
                            RTCRayN_tfar(ray, N, i) * len, &found))
            continue;
        RTCRayN_tfar(ray, N, i) = static_cast<float>(found.t / len);
        RTCHitN_Ng_x(hit, N, i) = static_cast<float>(found.normal.x);
        RTCHitN_Ng_y(hit, N, i) = static_cast<float>(found.normal.y);
        RTCHitN_Ng_z(hit, N, i) = static_cast<float>(found.normal.z);
        RTCHitN_u(hit, N, i) = static_cast<float>(material_of(found.part));
        RTCHitN_v(hit, N, i) = 0;
        RTCHitN_primID(hit, N, i) = args->primID;
        RTCHitN_geomID(hit, N, i) = args->geomID;
        RTCHitN_instID(hit, N, i, 0) = args->context->instID[0];
    }
}

void ProceduralLamps::occluded_callback(const RTCOccludedFunctionNArguments* args) {
    const auto* self = static_cast<const ProceduralLamps*>(args->geometryUserPtr);
    const unsigned N = args->N;
    for (unsigned i = 0; i < N; ++i) {
        if (args->valid[i] != -1) continue;
        const Vec3 origin{RTCRayN_org_x(args->ray, N, i), RTCRayN_org_y(args->ray, N, i),
                          RTCRayN_org_z(args->ray, N, i)};
        const Vec3 d{RTCRayN_dir_x(args->ray, N, i), RTCRayN_dir_y(args->ray, N, i), RTCRayN_dir_z(args->ray, N, i)};
        const double len = length(d);
        LampHit found;
        if (intersect_lamp(self->lamps_[args->primID], origin, d * (1 / len), RTCRayN_tnear(args->ray, N, i) * len,
                           RTCRayN_tfar(args->ray, N, i) * len, &found))
            RTCRayN_tfar(args->ray, N, i) = -std::numeric_limits<float>::infinity();
    }
}

RTCGeometry ProceduralLamps::create_embree_geometry(RTCDevice device) {
    lamps_.shrink_to_fit();
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(geometry, static_cast<unsigned>(lamps_.size()));
    rtcSetGeometryUserData(geometry, this);
    rtcSetGeometryBoundsFunction(geometry, bounds_callback, nullptr);
    rtcSetGeometryIntersectFunction(geometry, intersect_callback);
    rtcSetGeometryOccludedFunction(geometry, occluded_callback);
    return geometry;
}

void ProceduralLamps::complete_hit(const RTCHit& embree_hit, Hit& hit) const {
    hit.kind = ObjectKind::Lamp;
    hit.object = embree_hit.primID;
    hit.material = static_cast<uint16_t>(embree_hit.u);
    hit.geometric_normal = normalize(Vec3{embree_hit.Ng_x, embree_hit.Ng_y, embree_hit.Ng_z});
    hit.shading_normal = hit.geometric_normal;
}

}  // namespace citygen
