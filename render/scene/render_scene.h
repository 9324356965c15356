// The Embree scene the integrator traces, plus the table that turns an Embree hit (geomID,
// primID) back into a citygen Hit (object kind, object index, material, normals).
#pragma once

#include <atomic>
#include <memory>
#include <vector>

#include <embree3/rtcore.h>

#include "common/progress.h"
#include "render/scene/geometry_mode.h"
#include "render/scene/hit.h"
#include "render/scene/ray_recorder.h"
#include "render/scene/triangle_mesh.h"

namespace citygen {

// One Embree geometry and how to read its hits. Stored meshes and (later) procedural user
// geometry both implement this, so the integrator sees one kind of Hit.
class RenderGeometry {
public:
    virtual ~RenderGeometry() = default;
    virtual ObjectKind kind() const = 0;
    virtual GeometryMode mode() const = 0;
    // Creates the Embree geometry (not yet committed/attached); buffers may be shared with this
    // object, which outlives the Embree scene.
    virtual RTCGeometry create_embree_geometry(RTCDevice device) = 0;
    // Fills material, object index and normals of `hit` (t and position are already set) from
    // the Embree hit record of this geometry.
    virtual void complete_hit(const RTCHit& embree_hit, Hit& hit) const = 0;
    virtual uint64_t primitive_count() const = 0;  // triangles, or user primitives
    virtual uint64_t triangle_count() const = 0;   // 0 for procedural geometry
    virtual size_t buffer_bytes() const = 0;       // our own memory held for this geometry
    // The triangles, when this geometry is stored (for --export-ply); nullptr otherwise.
    virtual const TriangleMesh* stored_mesh() const { return nullptr; }
};

// Stored mode: a triangle mesh traced as RTC_GEOMETRY_TYPE_TRIANGLE.
class StoredMeshGeometry : public RenderGeometry {
public:
    explicit StoredMeshGeometry(TriangleMesh mesh);
    ObjectKind kind() const override { return mesh_.kind; }
    GeometryMode mode() const override { return GeometryMode::Stored; }
    RTCGeometry create_embree_geometry(RTCDevice device) override;
    void complete_hit(const RTCHit& embree_hit, Hit& hit) const override;
    uint64_t primitive_count() const override { return mesh_.triangle_count(); }
    uint64_t triangle_count() const override { return mesh_.triangle_count(); }
    size_t buffer_bytes() const override { return mesh_.bytes(); }
    const TriangleMesh* stored_mesh() const override { return &mesh_; }

private:
    TriangleMesh mesh_;
};

struct Box3 {
    Vec3 min{1e300, 1e300, 1e300}, max{-1e300, -1e300, -1e300};
    void extend(Vec3 p) {
        min = {std::fmin(min.x, p.x), std::fmin(min.y, p.y), std::fmin(min.z, p.z)};
        max = {std::fmax(max.x, p.x), std::fmax(max.y, p.y), std::fmax(max.z, p.z)};
    }
    bool empty() const { return min.x > max.x; }
};

class RenderScene {
public:
    RenderScene();
    ~RenderScene();
    RenderScene(const RenderScene&) = delete;
    RenderScene& operator=(const RenderScene&) = delete;

    RTCDevice device() const { return device_; }
    RTCScene embree_scene() const { return scene_; }  // committed; for tests/bench/ray_limit's replay
    void add(std::unique_ptr<RenderGeometry> geometry);
    // Builds the BVH, showing its progress as configured; call once after the last add().
    void commit(const ProgressSettings& progress = ProgressSettings{});

    // Closest hit in (tmin, tmax); thread-safe. `kind` only labels the ray for a recorder.
    bool intersect(const Ray& ray, Hit& hit, RayKind kind = RayKind::Bounce) const;
    // Any hit in (tmin, tmax); thread-safe.
    bool occluded(const Ray& ray) const;

    // While set, every intersect() and occluded() call appends its ray to `recorder` (null:
    // stop). For tests/bench/ray_limit; not to be changed while rays are traced.
    void set_ray_recorder(RayRecorder* recorder) { recorder_ = recorder; }

    Box3 bounds() const;  // of all geometry (empty if none)
    const std::vector<std::unique_ptr<RenderGeometry>>& geometries() const { return geometries_; }

    // Bytes Embree holds now (BVH and its own buffers), and the most it ever held.
    int64_t embree_bytes() const { return embree_bytes_.load(); }
    int64_t embree_peak_bytes() const { return embree_peak_bytes_.load(); }
    size_t buffer_bytes() const;  // sum of our own geometry buffers

private:
    static bool memory_monitor(void* self, ssize_t bytes, bool post);
    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
    std::vector<std::unique_ptr<RenderGeometry>> geometries_;  // index = Embree geomID
    std::atomic<int64_t> embree_bytes_{0}, embree_peak_bytes_{0};
    RayRecorder* recorder_ = nullptr;
};

}  // namespace citygen
