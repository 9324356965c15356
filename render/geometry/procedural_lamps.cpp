#include "render/geometry/procedural_lamps.h"

#include <limits>

#include "render/materials/materials.h"

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
    const StandingSurface surface(scene);
    for (const Lamp& lamp : scene.lamps) geometry->add(lamp_shape(lamp, lamp_ground(surface, lamp)));
    return geometry;
}

void ProceduralLamps::bounds(unsigned prim, RTCBounds* out) const {
    const LampShape& s = lamps_[prim];
    const double r = s.outer_radius() + 1e-3, pad = 1e-3;
    set_bounds(out, {s.base.x - r, s.base.y - r, s.base.z - pad}, {s.base.x + r, s.base.y + r, s.top() + pad});
}

bool ProceduralLamps::intersect(unsigned prim, Vec3 origin, Vec3 direction, double tmin, double tmax,
                                UserHit* hit) const {
    // The shape works with unit directions; t scales back by the direction's length.
    const double len = length(direction);
    LampHit found;
    if (!intersect_lamp(lamps_[prim], origin, direction * (1 / len), tmin * len, tmax * len, &found)) return false;
    hit->t = found.t / len;
    hit->normal = found.normal;
    hit->material = material_of(found.part);
    return true;
}

bool ProceduralLamps::occluded(unsigned prim, Vec3 origin, Vec3 direction, double tmin, double tmax) const {
    const double len = length(direction);
    LampHit found;
    return intersect_lamp(lamps_[prim], origin, direction * (1 / len), tmin * len, tmax * len, &found);
}

RTCGeometry ProceduralLamps::create_embree_geometry(RTCDevice device) {
    lamps_.shrink_to_fit();
    return new_user_geometry(device, this, lamps_.size());
}

void ProceduralLamps::complete_hit(const RTCHit& embree_hit, Hit& hit) const {
    complete_user_hit(embree_hit, ObjectKind::Lamp, embree_hit.primID, hit);
}

}  // namespace citygen
