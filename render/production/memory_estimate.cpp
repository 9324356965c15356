#include "render/production/memory_estimate.h"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <sys/resource.h>

#include "common/error.h"
#include "render/facade/facade_mesh.h"
#include "render/geometry/stored_geometry.h"
#include "render/geometry/terrain_geometry.h"
#include "render/geometry/tree_geometry.h"

namespace citygen {

namespace {

// Bytes of Embree and our buffers per stored triangle at the peak of the BVH build and per
// procedural primitive: what renders of our extracts held, rounded up (stored, with the compact
// BVH: Monaco 87, Kaiserslautern 74; docs/bench/2026-12-scale.md).
constexpr double kBytesPerTriangle = 96;
constexpr double kBytesPerPrimitive = 256;
// Headroom for the program, its libraries and the scene itself.
constexpr double kBaseBytes = 64.0 * 1024 * 1024;

double ring_points(const Building& b) {
    double n = static_cast<double>(b.outer.size());
    for (const Ring& h : b.holes) n += static_cast<double>(h.size());
    return n;
}

// A value from a "key: value kB" file such as /proc/meminfo, in bytes; < 0 when absent.
double proc_kilobytes(const char* file, const std::string& key) {
    std::ifstream in(file);
    for (std::string line; std::getline(in, line);)
        if (line.compare(0, key.size(), key) == 0) {
            std::istringstream value(line.substr(key.size()));
            double kb = -1;
            value >> kb;
            return kb * 1024;
        }
    return -1;
}

double read_number(const char* file) {  // -1 when absent or "max"
    std::ifstream in(file);
    double v = -1;
    if (!(in >> v)) return -1;
    return v;
}

}  // namespace

double wall_triangle_estimate(const WallLayout& layout) {
    // wall_triangle_count walks every cell, a million on an absurd wall: here the cells of each
    // kind are counted and one cell of each kind is triangulated (a cell's rectangles depend
    // only on its kind).
    FacadeRect rects[kMaxCellRects];
    double count = 2.0 * margin_rects(layout, rects);
    if (layout.plain()) return count;
    const double cells = static_cast<double>(layout.floors) * layout.slots;
    double of_kind[3] = {0, 0, 0};
    of_kind[static_cast<int>(CellKind::Shop)] = layout.shop ? layout.slots : 0;
    if (layout.balconies && layout.floors >= 2)
        of_kind[static_cast<int>(CellKind::Balcony)] =
            static_cast<double>(layout.floors - 1) * ((layout.slots + layout.balcony_every - 1) / layout.balcony_every);
    of_kind[static_cast<int>(CellKind::Window)] =
        cells - of_kind[static_cast<int>(CellKind::Shop)] - of_kind[static_cast<int>(CellKind::Balcony)];
    // Every kind present has a cell among these (windows: floor 0 without shops, else a
    // floor above on a slot without a balcony).
    const int candidates[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    bool counted[3] = {false, false, false};
    for (const auto& c : candidates) {
        if (c[0] >= layout.floors || c[1] >= layout.slots) continue;
        const int kind = static_cast<int>(cell_kind(layout, c[0], c[1]));
        if (counted[kind]) continue;
        counted[kind] = true;
        count += of_kind[kind] * 2.0 * cell_rects(layout, c[0], c[1], rects);
    }
    return count;
}

MemoryEstimate estimate_render_memory(const Scene& scene, const GeometryModes& modes, const FacadeOptions& facades,
                                      const RenderSettings& settings) {
    MemoryEstimate e;
    if (modes[GeometryClass::Buildings] == GeometryMode::Stored) {
        for (const Building& b : scene.buildings) {
            if (!has_volume(b)) continue;
            const BuildingWalls walls(b);
            for (size_t w = 0, n = walls.count(); w < n; ++w)
                e.stored_triangles += wall_triangle_estimate(make_wall_layout(facades, walls.input(w)));
            e.stored_triangles += 4 * ring_points(b);  // roof and underside, a bound
            for (const RoofFace& face : b.roof_faces) e.stored_triangles += static_cast<double>(face.points.size());
        }
    } else {
        for (const Building& b : scene.buildings) e.procedural_primitives += ring_points(b) + 2;
    }
    auto flat = [&](GeometryClass c, double points) {
        (modes[c] == GeometryMode::Stored ? e.stored_triangles : e.procedural_primitives) += points;
    };
    double road_points = 0, joint_points = 0, sidewalk_points = 0;
    for (const RoadEdge& r : scene.roads) road_points += static_cast<double>(r.quad.size());
    for (const Joint& j : scene.joints) joint_points += static_cast<double>(j.polygon.size());
    for (const Sidewalk& s : scene.sidewalks) sidewalk_points += 3 * static_cast<double>(s.polygon.size());  // + curbs
    flat(GeometryClass::Roads, road_points);
    flat(GeometryClass::Joints, joint_points);
    flat(GeometryClass::Sidewalks, sidewalk_points);
    double cover_points = 0, path_points = 0;
    for (const LandCover& c : scene.land_cover) {
        cover_points += static_cast<double>(c.outer.size());
        for (const Ring& h : c.holes) cover_points += static_cast<double>(h.size());
    }
    for (const PathEdge& p : scene.paths) path_points += static_cast<double>(p.quad.size());
    for (const Joint& j : scene.path_joints) path_points += static_cast<double>(j.polygon.size());
    flat(GeometryClass::LandCover, cover_points);
    flat(GeometryClass::Paths, path_points);
    // Lamps and trees: one primitive each, or the triangles of one, counted on a one-object
    // scene by the same code that builds them (their shapes have one definition).
    if (!scene.lamps.empty()) {
        if (modes[GeometryClass::Lamps] == GeometryMode::Stored) {
            Scene one;
            one.lamps.push_back(scene.lamps.front());
            e.stored_triangles += static_cast<double>(scene.lamps.size()) * build_stored_lamps(one).triangle_count();
        } else {
            e.procedural_primitives += static_cast<double>(scene.lamps.size());
        }
    }
    if (!scene.trees.empty()) {
        if (modes[GeometryClass::Trees] == GeometryMode::Stored) {
            Scene one;
            one.trees.push_back(scene.trees.front());
            e.stored_triangles += static_cast<double>(scene.trees.size()) * build_stored_trees(one)->triangle_count();
        } else {
            e.procedural_primitives += static_cast<double>(scene.trees.size());
        }
    }
    // The height field: two triangles a cell, or a primitive a block of cells plus the heights.
    if (!scene.terrain.empty()) {
        const double nodes = static_cast<double>(scene.terrain.nx) * scene.terrain.ny;
        const double cells = static_cast<double>(scene.terrain.nx - 1) * (scene.terrain.ny - 1);
        if (modes[GeometryClass::Terrain] == GeometryMode::Stored) e.stored_triangles += 2 * cells;
        else e.procedural_primitives += cells / (kTerrainBlock * kTerrainBlock) + nodes * sizeof(float) / kBytesPerPrimitive;
    }
    const double pixels = static_cast<double>(settings.width) * settings.height;
    // rgb floats, the AOVs (10 floats), the encoded copy and OpenImageIO's conversion buffer.
    e.image_bytes = pixels * 4 * (3 + (settings.aovs ? 10 : 0)) * 3;
    e.bytes = kBaseBytes + e.stored_triangles * kBytesPerTriangle + e.procedural_primitives * kBytesPerPrimitive +
              e.image_bytes;
    return e;
}

double available_memory_bytes() {
    double available = proc_kilobytes("/proc/meminfo", "MemAvailable:");
    if (available < 0) available = 1e18;
    struct rlimit limit;
    if (::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
        const double in_use = std::max(0.0, proc_kilobytes("/proc/self/status", "VmSize:"));
        available = std::min(available, static_cast<double>(limit.rlim_cur) - in_use);
    }
    const double cgroup_max = read_number("/sys/fs/cgroup/memory.max");
    if (cgroup_max > 0) {
        const double in_use = std::max(0.0, read_number("/sys/fs/cgroup/memory.current"));
        available = std::min(available, cgroup_max - in_use);
    }
    return std::max(0.0, available);
}

void check_memory_fits(const MemoryEstimate& estimate) {
    const double available = available_memory_bytes();
    if (estimate.bytes <= available) return;
    char message[400];
    std::snprintf(message, sizeof message,
                  "this render needs about %.1f GB of memory (%.0f M stored triangles, %.1f GB of image) but only "
                  "%.1f GB is available; try --procedural, a smaller image or a smaller scene",
                  estimate.bytes / 1e9, estimate.stored_triangles / 1e6, estimate.image_bytes / 1e9, available / 1e9);
    throw Error(message);
}

}  // namespace citygen
