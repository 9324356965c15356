// Shading-time detail on top of any geometry (either mode): a wrapper that lets the wrapped
// geometry complete a hit, then changes its material or shading normal from the hit's
// position (water waves, road markings). Both modes share the one detail function, so they
// show the same pattern.
#pragma once

#include <functional>
#include <memory>

#include "render/scene/render_scene.h"

namespace citygen {

class SurfaceDetailGeometry : public RenderGeometry {
public:
    using Detail = std::function<void(Hit&)>;
    SurfaceDetailGeometry(std::unique_ptr<RenderGeometry> inner, Detail detail)
        : inner_(std::move(inner)), detail_(std::move(detail)) {}
    ObjectKind kind() const override { return inner_->kind(); }
    GeometryMode mode() const override { return inner_->mode(); }
    RTCGeometry create_embree_geometry(RTCDevice device) override { return inner_->create_embree_geometry(device); }
    void complete_hit(const RTCHit& embree_hit, Hit& hit) const override {
        inner_->complete_hit(embree_hit, hit);
        detail_(hit);
    }
    uint64_t primitive_count() const override { return inner_->primitive_count(); }
    uint64_t triangle_count() const override { return inner_->triangle_count(); }
    size_t buffer_bytes() const override { return inner_->buffer_bytes(); }
    const TriangleMesh* stored_mesh() const override { return inner_->stored_mesh(); }

private:
    std::unique_ptr<RenderGeometry> inner_;
    Detail detail_;
};

}  // namespace citygen
