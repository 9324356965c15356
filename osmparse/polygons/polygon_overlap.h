// Overlap areas between road pieces and building footprints, and a grid to find the
// buildings near a polygon fast. Convex pieces clip the footprint directly (Sutherland-Hodgman
// gives the right area even for a non-convex footprint); other simple polygons are ear-clipped
// into triangles first. The decisions (which side, which ear, which building holds a point) are
// exact (exact_predicates.h); the areas are float constructions.
// Hand-written for speed: CGAL's Boolean intersection on exact constructions
// (overlap_area_exact in cgal_footprint.h) gives the same areas at many times the cost
// (tests/bench/footprint_bench; docs/bench/2026-11-buildings.md), and the road stages call this
// hundreds of thousands of times.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

#include "common/geometry.h"
#include "common/scene.h"
#include "osmparse/polygons/grid_cell_key.h"
#include "osmparse/polygons/ring_bands.h"

namespace citygen {

// Area of the part of `subject` (any simple polygon, either orientation) inside the
// convex polygon `clip`.
double clipped_area(const Ring& subject, const Ring& clip);

// The part of `subject` on the left of every directed line (a, b) (Sutherland-Hodgman).
// Exact for a result in one piece; callers check the ring is simple.
Ring clip_to_half_planes(const Ring& subject, const std::vector<std::pair<Vec2, Vec2>>& lines);

// Triangles (CCW) covering a simple polygon.
std::vector<Ring> triangulate(const Ring& polygon);

// A polygon kept elsewhere (a road quad, a joint, a sidewalk, a footprint), borrowed by an
// index: indexing road pieces this way copies none of their rings.
struct PolygonRef {
    const Ring* outer = nullptr;
    const std::vector<Ring>* holes = nullptr;  // null: none
};

// The quads of `edges` (roads or paths), then the polygons of their `joints`.
template <typename Edge>
std::vector<PolygonRef> surface_polygons(const std::vector<Edge>& edges, const std::vector<Joint>& joints) {
    std::vector<PolygonRef> out;
    out.reserve(edges.size() + joints.size());
    for (const Edge& e : edges) out.push_back({&e.quad});
    for (const Joint& j : joints) out.push_back({&j.polygon});
    return out;
}

// Area of a simple polygon `piece` that lies inside building `b` (outer minus holes).
double overlap_area(const Ring& piece, const PolygonRef& b);
inline double overlap_area(const Ring& piece, const Building& b) { return overlap_area(piece, {&b.outer, &b.holes}); }

// Buildings bucketed on a uniform grid by bounding box. Queries keep no state: several
// threads may query one index at once.
class BuildingIndex {
public:
    explicit BuildingIndex(const std::vector<Building>& buildings, double cell = 50);
    // Indexes borrowed polygons, which must outlive the index (their indices are the queries').
    explicit BuildingIndex(std::vector<PolygonRef> polygons, double cell = 50);
    // Indices of buildings whose bounding box overlaps `box`, ascending, no repeats.
    std::vector<uint32_t> near(const Box2& box) const;
    // Calls f(index) once for each of them, in grid order (no sorting, no allocation).
    // The cost is bounded by the number of buildings, never by the box's extent: a box
    // covering more cells than that (and than kMaxCellsPerObject) scans the buildings instead.
    template <typename F>
    void for_each_near(const Box2& box, F&& f) const {
        if (box.empty()) return;
        if (cells_spanned(box) > std::max(kMaxCellsPerObject, static_cast<double>(boxes_.size()))) {
            for (uint32_t i = 0; i < boxes_.size(); ++i)
                if (boxes_[i].overlaps(box)) f(i);
            return;
        }
        const Cell low{cell_of(box.min.x), cell_of(box.min.y)};
        for (int64_t cx = low.x; cx <= cell_of(box.max.x); ++cx)
            for (int64_t cy = low.y; cy <= cell_of(box.max.y); ++cy) {
                const CellRange cell = cell_at(grid_cell_key(cx, cy));
                for (uint32_t k = cell.begin; k != cell.end; ++k) {
                    const uint32_t i = members_[k];
                    // A building is listed in every cell its box spans: it is visited in the
                    // first of them the query reaches, so once, with no marks to keep.
                    const Cell first = first_cell_[i];
                    if (cx != std::max(low.x, first.x) || cy != std::max(low.y, first.y)) continue;
                    if (boxes_[i].overlaps(box)) f(i);
                }
            }
        for (uint32_t i : large_)
            if (boxes_[i].overlaps(box)) f(i);
    }
    // Sum over nearby buildings of overlap_area; the largest single overlap in `max_one`.
    double overlap(const Ring& piece, double* max_one = nullptr) const;
    bool contains(Vec2 p) const;  // inside some building's footprint (not in a hole)
    const PolygonRef& polygon(uint32_t i) const { return polygons_[i]; }  // the i-th indexed
    size_t cell_count() const { return cell_count_; }  // grid cells in use (for tests)
    // An object covering more cells than this is kept in one list that every query checks,
    // so no object's extent decides the index's memory or build time.
    static constexpr double kMaxCellsPerObject = 4096;

private:
    bool in_ring(Vec2 p, const Ring& ring) const;  // exact_point_in_ring, from the bands of a long ring

    struct Cell {
        int64_t x = 0, y = 0;
    };
    double cells_spanned(const Box2& box) const {  // in double: a box may be absurdly large
        return (std::floor(box.max.x / cell_) - std::floor(box.min.x / cell_) + 1) *
               (std::floor(box.max.y / cell_) - std::floor(box.min.y / cell_) + 1);
    }
    int64_t cell_of(double v) const { return static_cast<int64_t>(std::floor(v / cell_)); }
    // The grid is flat (no container per cell; indexes are built a dozen times per parse):
    // the buildings of each cell lie together in members_, ascending, and an open-addressing
    // table finds a cell's run from its key.
    struct CellRange {
        uint32_t begin = 0, end = 0;
    };
    struct Slot {
        int64_t key = 0;
        CellRange range;  // empty: the slot is free
    };
    static uint64_t slot_hash(int64_t key) { return static_cast<uint64_t>(key) * 0x9E3779B97F4A7C15ull; }
    CellRange cell_at(int64_t key) const {
        if (slots_.empty()) return {};
        for (size_t s = slot_hash(key) >> shift_;; s = (s + 1) & (slots_.size() - 1)) {
            const Slot& slot = slots_[s];
            if (slot.range.begin == slot.range.end || slot.key == key) return slot.key == key ? slot.range : CellRange{};
        }
    }
    std::vector<PolygonRef> polygons_;
    std::vector<Box2> boxes_;
    std::vector<Cell> first_cell_;  // the lowest cell of each box, on both axes
    double cell_;
    std::vector<uint32_t> members_;  // buildings by cell
    std::vector<Slot> slots_;        // a power of two, at most half full
    int shift_ = 64;                 // slot_hash(key) >> shift_: the first slot to probe
    size_t cell_count_ = 0;
    std::vector<uint32_t> large_;  // objects spanning more than kMaxCellsPerObject cells
    std::unordered_map<const Ring*, RingBands> bands_;  // the long rings' (the sea's, a forest's)
};

}  // namespace citygen
