#include "render/facade/facade_mesh.h"

namespace citygen {

namespace {

// Wall-local point of a rectangle corner: (a, b) are the rectangle's two free coordinates.
Vec3 rect_point(const FacadeRect& r, double a, double b) {
    switch (r.axis) {
        case 0: return {r.at, a, b};
        case 1: return {a, r.at, b};
        default: return {a, b, r.at};
    }
}

void append_rect(const FacadeRect& r, const WallFrame& frame, FacadeMesh& mesh) {
    Vec3 corners[4] = {rect_point(r, r.a0, r.b0), rect_point(r, r.a1, r.b0), rect_point(r, r.a1, r.b1),
                       rect_point(r, r.a0, r.b1)};
    Vec3 local_normal;
    if (r.axis == 0) local_normal = {double(r.normal_sign), 0, 0};
    if (r.axis == 1) local_normal = {0, double(r.normal_sign), 0};
    if (r.axis == 2) local_normal = {0, 0, double(r.normal_sign)};
    const uint32_t base = static_cast<uint32_t>(mesh.vertices.size());
    for (Vec3 c : corners) mesh.vertices.push_back(frame.to_world(c.x, c.y, c.z));
    // Wind the quad so that its geometric normal (e1 x e2) is the rectangle's normal in world
    // space; the frame may be left- or right-handed.
    const Vec3* p = &mesh.vertices[base];
    const bool flip = dot(cross(p[1] - p[0], p[2] - p[0]), frame.direction_to_world(local_normal)) < 0;
    if (flip) {
        mesh.triangles.push_back({base, base + 2, base + 1});
        mesh.triangles.push_back({base, base + 3, base + 2});
    } else {
        mesh.triangles.push_back({base, base + 1, base + 2});
        mesh.triangles.push_back({base, base + 2, base + 3});
    }
    mesh.surfaces.push_back(r.surface);
    mesh.surfaces.push_back(r.surface);
}

}  // namespace

void append_wall_mesh(const WallLayout& layout, const WallFrame& frame, FacadeMesh& mesh) {
    FacadeRect rects[kMaxCellRects];
    int n = margin_rects(layout, rects);
    for (int i = 0; i < n; ++i) append_rect(rects[i], frame, mesh);
    for (int floor = 0; floor < layout.floors; ++floor) {
        for (int slot = 0; slot < layout.slots; ++slot) {
            n = cell_rects(layout, floor, slot, rects);
            for (int i = 0; i < n; ++i) append_rect(rects[i], frame, mesh);
        }
    }
}

size_t wall_triangle_count(const WallLayout& layout) {
    FacadeRect rects[kMaxCellRects];
    size_t count = 2 * static_cast<size_t>(margin_rects(layout, rects));
    for (int floor = 0; floor < layout.floors; ++floor)
        for (int slot = 0; slot < layout.slots; ++slot) count += 2 * static_cast<size_t>(cell_rects(layout, floor, slot, rects));
    return count;
}

}  // namespace citygen
