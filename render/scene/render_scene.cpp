#include "render/scene/render_scene.h"

#include <algorithm>
#include <cstring>
#include <string>

#include "common/error.h"
#include "render/materials/materials.h"

namespace citygen {

namespace {

void embree_error(void*, RTCError code, const char* message) {
    // Embree reports through this callback; the calling code checks rtcGetDeviceError where it
    // matters, so only report here.
    std::fprintf(stderr, "render: embree error %d: %s\n", static_cast<int>(code), message ? message : "");
}

// Embree reports a BVH build as a fraction in [0, 1], possibly from several threads at once and
// not always increasing; the bar moves forward by the largest fraction seen.
struct BvhProgress {
    static constexpr uint64_t kSteps = 1000;
    Progress bar;
    std::atomic<uint64_t> reported{0};
    static bool monitor(void* self_ptr, double fraction) {
        auto* self = static_cast<BvhProgress*>(self_ptr);
        const uint64_t now = static_cast<uint64_t>(std::clamp(fraction, 0.0, 1.0) * kSteps);
        uint64_t before = self->reported.load();
        while (now > before && !self->reported.compare_exchange_weak(before, now)) {
        }
        if (now > before) self->bar.advance(now - before);
        return true;  // never cancel the build
    }
};

}  // namespace

StoredMeshGeometry::StoredMeshGeometry(TriangleMesh mesh) : mesh_(std::move(mesh)) {
    // Embree reads vertex buffers with 16-byte loads: pad past the last vertex.
    mesh_.vertices.reserve(mesh_.vertices.size() + 4);
    mesh_.vertices.insert(mesh_.vertices.end(), {0.f, 0.f, 0.f, 0.f});
    mesh_.vertices.resize(mesh_.vertices.size() - 4);
}

RTCGeometry StoredMeshGeometry::create_embree_geometry(RTCDevice device) {
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                               mesh_.vertices.data(), 0, 3 * sizeof(float), mesh_.vertex_count());
    rtcSetSharedGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                               mesh_.indices.data(), 0, 3 * sizeof(uint32_t), mesh_.triangle_count());
    return geometry;
}

void StoredMeshGeometry::complete_hit(const RTCHit& embree_hit, Hit& hit) const {
    const uint32_t prim = embree_hit.primID;
    hit.kind = mesh_.kind;
    hit.object = mesh_.face_object[prim];
    hit.material = mesh_.face_material[prim];
    // The front side is the counter-clockwise one (our own convention, independent of Embree's).
    const Vec3 a = mesh_.vertex(mesh_.indices[3 * prim]);
    const Vec3 b = mesh_.vertex(mesh_.indices[3 * prim + 1]);
    const Vec3 c = mesh_.vertex(mesh_.indices[3 * prim + 2]);
    hit.geometric_normal = normalize(cross(b - a, c - a));
    hit.shading_normal = hit.geometric_normal;
    if (!mesh_.pane_cells.empty() && (hit.material == kGlass || hit.material == kShopWindow)) {
        auto after = std::upper_bound(mesh_.pane_cells.begin(), mesh_.pane_cells.end(), prim,
                                      [](uint32_t p, const TriangleMesh::PaneCell& c) { return p < c.first_triangle; });
        if (after != mesh_.pane_cells.begin() && prim < std::prev(after)->first_triangle + 2) {
            hit.wall = std::prev(after)->wall;
            hit.cell = std::prev(after)->cell;
        }
    }
}

RenderScene::RenderScene() {
    device_ = rtcNewDevice(nullptr);
    if (!device_) throw Error("cannot create an Embree device");
    rtcSetDeviceErrorFunction(device_, embree_error, nullptr);
    rtcSetDeviceMemoryMonitorFunction(device_, &RenderScene::memory_monitor, this);
    scene_ = rtcNewScene(device_);
    // The compact BVH keeps triangles as indices into our vertex buffer instead of copying them
    // out: stored cities are mostly triangles, and memory is what limits their size.
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_COMPACT);
}

RenderScene::~RenderScene() {
    if (scene_) rtcReleaseScene(scene_);
    if (device_) rtcReleaseDevice(device_);
}

bool RenderScene::memory_monitor(void* self_ptr, ssize_t bytes, bool) {
    auto* self = static_cast<RenderScene*>(self_ptr);
    const int64_t now = self->embree_bytes_.fetch_add(bytes) + bytes;
    int64_t peak = self->embree_peak_bytes_.load();
    while (now > peak && !self->embree_peak_bytes_.compare_exchange_weak(peak, now)) {
    }
    return true;
}

void RenderScene::add(std::unique_ptr<RenderGeometry> geometry) {
    if (geometry->primitive_count() == 0) return;
    RTCGeometry g = geometry->create_embree_geometry(device_);
    rtcCommitGeometry(g);
    const unsigned id = rtcAttachGeometry(scene_, g);
    rtcReleaseGeometry(g);
    if (id != geometries_.size()) throw Error("internal: Embree geometry ids out of order");
    geometries_.push_back(std::move(geometry));
}

void RenderScene::commit(const ProgressSettings& settings) {
    BvhProgress bvh{Progress("BVH", BvhProgress::kSteps, settings)};
    rtcSetSceneProgressMonitorFunction(scene_, &BvhProgress::monitor, &bvh);
    rtcCommitScene(scene_);
    rtcSetSceneProgressMonitorFunction(scene_, nullptr, nullptr);
    bvh.bar.finish();
    const RTCError err = rtcGetDeviceError(device_);
    if (err != RTC_ERROR_NONE)
        throw Error("Embree could not build the scene (error " + std::to_string(err) + ")");
}

namespace {

RTCRay embree_ray(const Ray& ray) {
    RTCRay r;
    r.org_x = static_cast<float>(ray.origin.x);
    r.org_y = static_cast<float>(ray.origin.y);
    r.org_z = static_cast<float>(ray.origin.z);
    r.dir_x = static_cast<float>(ray.direction.x);
    r.dir_y = static_cast<float>(ray.direction.y);
    r.dir_z = static_cast<float>(ray.direction.z);
    r.tnear = static_cast<float>(ray.tmin);
    r.tfar = static_cast<float>(ray.tmax);
    r.time = 0;
    r.mask = 0xFFFFFFFFu;
    r.id = 0;
    r.flags = 0;
    return r;
}

// `sent` is the ray as it went to Embree (before Embree shortened tfar).
void record(RayRecorder& recorder, const RTCRay& sent, RayKind kind, bool hit) {
    recorder.record({{sent.org_x, sent.org_y, sent.org_z}, {sent.dir_x, sent.dir_y, sent.dir_z}, sent.tnear,
                     sent.tfar, kind, hit});
}

}  // namespace

bool RenderScene::intersect(const Ray& ray, Hit& hit, RayKind kind) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rh;
    rh.ray = embree_ray(ray);
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &context, &rh);
    const bool found = rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    if (recorder_) record(*recorder_, embree_ray(ray), kind, found);
    if (!found) return false;
    hit.t = rh.ray.tfar;
    hit.position = ray.origin + ray.direction * hit.t;
    geometries_[rh.hit.geomID]->complete_hit(rh.hit, hit);
    return true;
}

bool RenderScene::occluded(const Ray& ray) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay r = embree_ray(ray);
    rtcOccluded1(scene_, &context, &r);
    const bool blocked = r.tfar < 0;  // Embree sets tfar to -inf on a hit
    if (recorder_) record(*recorder_, embree_ray(ray), RayKind::Shadow, blocked);
    return blocked;
}

Box3 RenderScene::bounds() const {
    RTCBounds b;
    rtcGetSceneBounds(scene_, &b);
    Box3 box;
    if (geometries_.empty()) return box;
    box.extend({b.lower_x, b.lower_y, b.lower_z});
    box.extend({b.upper_x, b.upper_y, b.upper_z});
    return box;
}

size_t RenderScene::buffer_bytes() const {
    size_t total = 0;
    for (const auto& g : geometries_) total += g->buffer_bytes();
    return total;
}

}  // namespace citygen
