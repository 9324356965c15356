// Procedural geometry mode for street lamps: one Embree user primitive per lamp, whose callback
// intersects the lamp shape (lamp_shape.h) analytically: pole and cap rim as cylinders, the
// globe as a sphere, the cap's top and underside as disks. Per lamp only the shape is kept.
#pragma once

#include <memory>
#include <vector>

#include "common/scene.h"
#include "render/geometry/lamp_shape.h"
#include "render/scene/render_scene.h"
#include "render/scene/user_geometry.h"

namespace citygen {

class ProceduralLamps : public RenderGeometry {
public:
    void add(const LampShape& shape) { lamps_.push_back(shape); }

    ObjectKind kind() const override { return ObjectKind::Lamp; }
    GeometryMode mode() const override { return GeometryMode::Procedural; }
    RTCGeometry create_embree_geometry(RTCDevice device) override;
    void complete_hit(const RTCHit& embree_hit, Hit& hit) const override;
    uint64_t primitive_count() const override { return lamps_.size(); }
    uint64_t triangle_count() const override { return 0; }
    size_t buffer_bytes() const override { return lamps_.capacity() * sizeof(LampShape); }

    // What the Embree callbacks (user_geometry.h) compute per lamp.
    void bounds(unsigned prim, RTCBounds* out) const;
    bool intersect(unsigned prim, Vec3 origin, Vec3 direction, double tmin, double tmax, UserHit* hit) const;
    bool occluded(unsigned prim, Vec3 origin, Vec3 direction, double tmin, double tmax) const;

private:
    std::vector<LampShape> lamps_;  // index = lamp index in the scene file
};

std::unique_ptr<ProceduralLamps> build_procedural_lamps(const Scene& scene);

}  // namespace citygen
