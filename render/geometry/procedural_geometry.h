// Procedural geometry mode: Embree user geometry whose surfaces are computed inside the
// intersect and occluded callbacks instead of being stored as triangles.
//
// The primitives, all tiny:
//   - a wall: a WallLayout + WallFrame (render/facade/facade.h); the callback runs the cell-walking
//     intersector (render/facade/wall_intersect.h), so windows, balconies and shop fronts exist only
//     for the rays that reach them. Bounds = the wall's slab including recess and balcony depth.
//     A plain wall (a facade too small for windows) has no layout: a bare vertical rectangle.
//   - a flat polygon (roof, building underside, road, joint, sidewalk, ground): plane hit +
//     point-in-polygon, holes included; a sidewalk's with its curb faces as plain walls.
//   - a planar face in any orientation (roof faces, gable walls, draped ground).
// The builders mirror the stored builders (stored_geometry.h) surface for surface, so both
// modes give the same Hit (kind, object index, material, normal) for the same ray.
// A hit stores the surface's material id in RTCHit::u (an integer, exact in a float) and the
// facade cell in RTCHit::v (floor * 65536 + slot + 1, 0 off the grid). No allocation happens
// inside the callbacks.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "common/progress.h"
#include "common/scene.h"
#include "render/facade/facade.h"
#include "render/scene/render_scene.h"
#include "render/scene/user_geometry.h"

namespace citygen {

class ProceduralGeometry : public RenderGeometry {
public:
    // Material id for each facade surface kind (index = FacadeSurface value).
    using SurfaceMaterials = std::array<uint16_t, kFacadeSurfaceCount>;

    ProceduralGeometry(ObjectKind kind, const SurfaceMaterials& wall_materials);

    // `object` is the index of the scene object the primitive belongs to (reported for hits).
    // A building's facade choices, shared by its walls: add_wall's `choices`.
    uint32_t add_facade_choices(const FacadeChoices& choices);
    // The wall `wall` (its index within its building is reported for pane hits) with this grid
    // (plain or not) stands on the edge a->b from z = bottom (its frame is wall_frame(a, b, bottom)).
    // Its layout is wall_layout(choices, grid, ...), made again whenever a ray needs it.
    void add_wall(uint32_t object, const WallInput& wall, uint32_t choices, const WallGrid& grid, Vec2 a, Vec2 b,
                  double bottom);
    void reserve_walls(size_t count) { walls_.reserve(count); }  // no regrowth of the largest array
    // A horizontal polygon at height z facing up (normal_z = +1) or down (-1); any orientation.
    void add_polygon(uint32_t object, const Ring& outer, const std::vector<Ring>& holes, double z, uint16_t material,
                     int normal_z = +1);
    // A polygon at z facing up whose outline stands on a curb: every edge a bare vertical
    // rectangle from curb_bottom up to z facing out (the Wall surface's material), all in one
    // primitive (a sidewalk piece is one primitive, not one per edge).
    void add_curbed_polygon(uint32_t object, const Ring& outer, double z, uint16_t material, double curb_bottom);
    // A planar polygon in any orientation (roof faces, gable walls), front side counter-clockwise:
    // plane hit plus point-in-polygon in the plane's projection along its dominant axis.
    void add_face(uint32_t object, const std::vector<Vec3>& points, uint16_t material);
    // Adds the surfaces of `part` (of the same kind) after those already here, as if they had
    // been added here in its order: builders make runs of objects side by side and join them.
    void append(const ProceduralGeometry& part);

    ObjectKind kind() const override { return kind_; }
    GeometryMode mode() const override { return GeometryMode::Procedural; }
    RTCGeometry create_embree_geometry(RTCDevice device) override;
    void complete_hit(const RTCHit& embree_hit, Hit& hit) const override;
    uint64_t primitive_count() const override {
        return walls_.size() + polygons_.size() + faces_.size();
    }
    uint64_t triangle_count() const override { return 0; }
    size_t buffer_bytes() const override;

    size_t wall_count() const { return walls_.size(); }
    size_t polygon_count() const { return polygons_.size(); }
    size_t face_count() const { return faces_.size(); }
    // Surface ids (the primitive ids hits report): walls, then polygons, then faces.
    uint32_t object(unsigned prim_id) const {
        if (prim_id < walls_.size()) return walls_[prim_id].object;
        prim_id -= static_cast<unsigned>(walls_.size());
        if (prim_id < polygons_.size()) return polygons_[prim_id].object;
        return faces_[prim_id - polygons_.size()].object;
    }

    // What the Embree callbacks (user_geometry.h) compute, in double precision, for Embree's
    // primitives: runs of walls (wall_runs_), then polygons, then faces.
    using PrimitiveHit = UserHit;
    void bounds(unsigned prim_id, RTCBounds* out) const;
    bool intersect(unsigned prim_id, Vec3 origin, Vec3 direction, double tmin, double tmax, PrimitiveHit* hit) const;
    bool occluded(unsigned prim_id, Vec3 origin, Vec3 direction, double tmin, double tmax) const;

    // Up to this many walls of one object, side by side along its outline, are one Embree
    // primitive: the BVH over millions of walls then holds fewer primitives (its memory, and
    // its build's more so), and a ray entering a run's box tests its walls one after another.
    // Two keeps that extra work small; longer runs save less memory for more time.
    static constexpr uint32_t kWallsPerRun = 2;

private:
    // A wall keeps its frame as the numbers it is made of, and its layout as its grid and its
    // building's choices (by index): a city holds millions of walls, a third of them plain.
    struct Wall {
        Vec3 origin;  // lower end of a
        Vec2 along;   // unit direction a->b
        double length, height;
        uint32_t object, wall_index;
        uint32_t grid;     // into grids_, or kPlainWall
        uint32_t choices;  // into choices_ (walls with a grid only)
    };
    static constexpr uint32_t kPlainWall = 0xffffffffu;
    // Millions of values in blocks of fixed size: a vector's regrowth and final shrink would
    // hold them twice for a moment, at the render's peak.
    template <class T>
    class Blocks {
    public:
        uint32_t push_back(const T& value) {
            if ((size_ & kMask) == 0) blocks_.push_back(std::make_unique<T[]>(kBlock));
            blocks_.back()[size_ & kMask] = value;
            return size_++;
        }
        const T& operator[](uint32_t i) const { return blocks_[i >> kShift][i & kMask]; }
        uint32_t size() const { return size_; }
        size_t bytes() const { return blocks_.size() * kBlock * sizeof(T); }

    private:
        static constexpr uint32_t kShift = 8, kBlock = 1u << kShift, kMask = kBlock - 1;
        std::vector<std::unique_ptr<T[]>> blocks_;
        uint32_t size_ = 0;
    };
    struct Polygon {
        uint32_t first_ring, ring_count;  // into ring_ends_; the first ring is the outer one
        uint32_t hole_root;               // into hole_nodes_, or kNoHoleTree: the holes one by one
        double z;
        Box2 bounds;
        uint32_t object;
        uint16_t material;
        int8_t normal_z;
        bool curbed = false;  // its outer ring's edges are plain walls from curb_bottom up to z
        double curb_bottom = 0;
    };
    struct Face {
        uint32_t first_point, point_count;  // into face_points_ (projected on axes u, v)
        Vec3 normal;                        // unit, front side
        double offset;                      // plane: dot(normal, p) = offset
        uint8_t axis_u, axis_v;             // the two world axes the polygon is projected on
        Vec3 lo, hi;                        // bounds
        uint32_t object;
        uint16_t material;
    };
    // A bounding-box tree over one polygon's holes (built when it has more than kHoleTreeMin), so
    // that a point is tested against the few holes whose box holds it, not against every hole.
    // A leaf (count > 0) holds hole_rings_[first, first + count); an inner node's children are the
    // next node and node `first`.
    struct HoleNode {
        Box2 box;
        uint32_t first, count;
    };
    static constexpr uint32_t kNoHoleTree = 0xffffffffu;
    static constexpr size_t kHoleTreeMin = 16, kHoleLeafSize = 4;
    // The same, one surface at a time (ids as object() takes them).
    void surface_bounds(uint32_t surface, Vec3* lo, Vec3* hi) const;
    bool intersect_surface(uint32_t surface, Vec3 origin, Vec3 direction, double tmin, double tmax,
                           PrimitiveHit* hit) const;
    bool surface_occluded(uint32_t surface, Vec3 origin, Vec3 direction, double tmin, double tmax) const;
    // Embree primitive -> its first surface, and the number of surfaces it holds.
    uint32_t first_surface(unsigned prim_id, uint32_t* count) const;
    bool in_ring(uint32_t ring, Vec2 p) const;
    bool in_some_hole(uint32_t root, Vec2 p) const;
    bool intersect_face(const Face& face, Vec3 origin, Vec3 direction, double tmin, double tmax, double* t) const;
    bool inside_polygon(const Polygon& polygon, Vec2 p) const;
    // The nearest curb face of a curbed polygon hit in [tmin, tmax].
    bool intersect_curbs(const Polygon& polygon, Vec3 origin, Vec3 direction, double tmin, double tmax,
                         PrimitiveHit* hit) const;
    // f(layout, frame) of wall `index`. The rays of a pixel, and its neighbours', meet the same
    // walls again and again: each thread keeps the layouts it made last (values only, so nothing
    // seen depends on the cache or the thread count).
    template <class F>
    auto with_wall(uint32_t index, F&& f) const {
        const Wall& wall = walls_[index];
        const WallFrame frame = wall_frame(wall.origin, wall.along);
        if (wall.grid == kPlainWall) {
            WallLayout plain;
            plain.length = wall.length;
            plain.height = wall.height;
            return f(plain, frame);
        }
        struct Cached {
            uint64_t owner = 0;
            uint32_t wall = 0;
            WallLayout layout;
        };
        thread_local Cached cache[16];
        Cached& slot = cache[index & 15];
        if (slot.owner != id_ || slot.wall != index) {
            slot.owner = id_;
            slot.wall = index;
            slot.layout = wall_layout(choices_[wall.choices], grids_[wall.grid], wall.length, wall.height);
        }
        return f(slot.layout, frame);
    }

    ObjectKind kind_;
    uint64_t id_;  // tells this instance's layouts in the per-thread cache from others'
    SurfaceMaterials wall_materials_;
    std::vector<Wall> walls_;
    // Where each run of walls starts, and walls_.size() at the end (made by create_embree_geometry).
    std::vector<uint32_t> wall_runs_;
    Blocks<WallGrid> grids_;          // of the walls with windows
    Blocks<FacadeChoices> choices_;   // of the buildings with windows
    std::vector<Polygon> polygons_;
    std::vector<Face> faces_;
    std::vector<Vec2> face_points_;    // all faces' projected points, back to back
    std::vector<Vec2> points_;         // all polygon rings, back to back
    std::vector<uint32_t> ring_ends_;  // end (exclusive) of each ring in points_
    std::vector<HoleNode> hole_nodes_;
    std::vector<uint32_t> hole_rings_;  // ring indices (into ring_ends_), in the trees' leaf order
};

// Procedural builders, one per object class, producing the same surfaces as build_stored_*.
// `progress` (optional) advances once per building.
std::unique_ptr<ProceduralGeometry> build_procedural_buildings(const Scene& scene, const FacadeOptions& facades,
                                                               Progress* progress = nullptr);
std::unique_ptr<ProceduralGeometry> build_procedural_roads(const Scene& scene);
std::unique_ptr<ProceduralGeometry> build_procedural_joints(const Scene& scene);
std::unique_ptr<ProceduralGeometry> build_procedural_sidewalks(const Scene& scene);
std::unique_ptr<ProceduralGeometry> build_procedural_terrain(const Scene& scene);

// The procedural twin of add_ground_polygon (stored_geometry.h): one flat polygon without a
// field, the draped triangles as faces with one.
void add_ground_polygon(const Scene& scene, const Ring& outer, const std::vector<Ring>& holes, double lift,
                        uint32_t object, uint16_t material, ProceduralGeometry& geometry);

}  // namespace citygen
