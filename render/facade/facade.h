// The facade rules: the one definition of windows, balconies and shop fronts on a wall.
//
// Both geometry modes use them: the stored mode triangulates them (facade_mesh.h), the
// procedural mode intersects them analytically (wall_intersect.h). Every surface of a wall is
// an axis-aligned rectangle in wall-local coordinates (u along the wall, v up, w into the
// building), produced by cell_rects() and margin_rects() below; both modes consume exactly
// these rectangles, so they agree by construction.
//
// A facade is a regular grid of cells (floors x slots) inside margins at the wall edges, the
// bottom (plinth) and the top (parapet). Every cell holds one opening recessed into the wall
// with a room box behind it; all geometry of a cell stays inside the cell's (u, v) rectangle,
// which is what lets the intersector walk only the cells a ray crosses.
#pragma once

#include <algorithm>

#include <cstdint>
#include <vector>

#include "common/geometry.h"
#include "common/scene.h"

namespace citygen {

// What a facade surface is; the renderer maps each kind to a material.
enum class FacadeSurface : uint8_t {
    Wall = 0,     // the facade plane around the openings
    Reveal,       // the sides of a recessed opening (wall material)
    Glass,        // window pane
    Room,         // inside of the room box behind an opening (glows at night)
    BalconySlab,  // balcony floor slab
    Fence,        // balcony railing (a thin panel)
    BalconyDoor,  // glass door onto a balcony
    ShopWindow,   // large ground-floor shop pane
};
constexpr int kFacadeSurfaceCount = 8;
const char* to_string(FacadeSurface surface);

struct FacadeOptions {
    uint64_t seed = 0;
    double shop_probability = 0.3;  // chance that a building has a ground floor of shop windows
};

// The kind of facade a building gets, from its type, wall material and height (facade_style):
// plain walls for garages, sheds and industry; curtain-wall glass for glass walls and tall
// offices; ribbon windows in narrow bays and tall storeys, no balconies, for other offices;
// low storeys, wide bays and never a shop front for houses; shop fronts always for shops.
enum class FacadeStyle : uint8_t { Normal = 0, Plain, CurtainWall, House, Shops, Office };
FacadeStyle facade_style(const Building& building);

// What a wall is, as far as the rules care. Walls are numbered over the outer ring's edges
// first, then each hole's edges in order (see building_wall_count / building_wall).
struct WallInput {
    uint64_t building_key = 0;  // facade_building_key(building)
    uint32_t wall_index = 0;
    double length = 0;          // metres along the wall
    double bottom_z = 0;        // building min_height
    double height = 0;          // top minus bottom
    int levels = 0;             // tagged building:levels, 0 when unknown
    // Interior angles (radians) of the footprint at the wall's two ends; below a right angle
    // the neighbouring wall cuts in behind this one, so room boxes must be shallower.
    double start_angle = kPi, end_angle = kPi;
    FacadeStyle style = FacadeStyle::Normal;
};

// An opening (or any rectangle) in cell-relative (u, v): [u0, u1] x [v0, v1].
struct CellRect {
    double u0 = 0, u1 = 0, v0 = 0, v1 = 0;
};

enum class CellKind : uint8_t { Window = 0, Balcony = 1, Shop = 2 };

// Everything needed to build or intersect one wall: a few numbers, no per-window storage.
struct WallLayout {
    // Sizes every gridded wall shares, and those that follow from the grid: kept out of the
    // struct so that the million walls of a metropolis hold only what differs between them.
    static constexpr double kRoomInset = 0.08;     // room box = cell shrunk by this on every side
    static constexpr double kSlabThickness = 0.18;
    static constexpr double kBalconyMargin = 0.1;  // slab is the cell width minus this on each side

    double length = 0, height = 0;
    int floors = 0, slots = 0;            // 0 when the wall is plain
    double grid_u0 = 0, grid_v0 = 0;      // lower-left corner of the cell grid (the margins)
    double slot_width = 0, floor_height = 0;
    double recess = 0;                    // depth of the pane behind the facade plane
    double room_depth = 0;                // depth of the room box behind the pane
    CellRect window;                      // cell-relative opening of a window
    int balcony_every = 1;                // balcony in slots where slot % every == 0 (floors >= 1)
    bool balconies = false;
    bool shop = false;                    // floor 0 is a row of shop windows
    double balcony_depth = 0;             // how far the slab sticks out (towards -w)
    CellRect door;                        // cell-relative balcony door opening

    double fence_height() const { return std::min(1.0, floor_height - 1.0); }
    CellRect shop_window() const { return {0.25, slot_width - 0.25, 0.4, floor_height - 0.5}; }  // cell-relative
    bool plain() const { return floors <= 0 || slots <= 0; }
    double grid_u1() const { return grid_u0 + slots * slot_width; }
    double grid_v1() const { return grid_v0 + floors * floor_height; }
    // The slab of w that holds every surface: balconies stick out, rooms go in.
    double w_min() const { return balconies ? -balcony_depth : 0.0; }
    double w_max() const { return plain() ? 0.0 : recess + room_depth; }
};

// A key for a building's facade randomness that does not depend on its index in the file.
uint64_t facade_building_key(const Building& building);

// THE rules: derive a wall's layout from (seed, building key, wall index) and its size.
WallLayout make_wall_layout(const FacadeOptions& options, const WallInput& wall);

// make_wall_layout in three steps, for a city's millions of walls: what the rules choose once per
// building (every wall of a building shares its style, so floors line up at corners), what they
// choose per wall (its grid: 40 bytes), and the layout made from both (whenever it is needed).
struct FacadeChoices {
    FacadeStyle style = FacadeStyle::Normal;
    double bottom_margin = 0, top_margin = 0, edge_margin = 0;
    double floor_target = 0, slot_target = 0;      // storey height and bay width aimed at
    double recess = 0, room_depth = 0;
    double window_width = 0, sill = 0, window_height = 0, ribbon = 0;  // before a slot or storey bounds them
    bool balconies = false;                        // on some of its walls
    int balcony_every = 1;
    double balcony_depth = 0, door_width = 0;
    bool shop = false;                             // where a wall allows a shop front
};
struct WallGrid {
    int floors = 0, slots = 0;  // 0: a plain wall
    double slot_width = 0, floor_height = 0, room_depth = 0;
    bool balconies = false, shop = false;
    bool plain() const { return floors <= 0 || slots <= 0; }
};
FacadeChoices facade_choices(const FacadeOptions& options, uint64_t building_key, FacadeStyle style);
WallGrid wall_grid(const FacadeOptions& options, const FacadeChoices& choices, const WallInput& wall);
WallLayout wall_layout(const FacadeChoices& choices, const WallGrid& grid, double length, double height);

CellKind cell_kind(const WallLayout& layout, int floor, int slot);

// Whether the window of cell (floor, slot) is lit at night: a pure function of (seed, building
// key, wall index, cell) and the share asked for, so both geometry modes, any thread count and
// the light sampler see the same lit windows. Windows and balcony doors are lit with
// probability lit_share, shop fronts (open late, lit displays) more often: sqrt(lit_share).
bool window_lit(const FacadeOptions& options, uint64_t building_key, uint32_t wall_index, const WallLayout& layout,
                int floor, int slot, double lit_share);

// An axis-aligned rectangle in wall-local space: coordinate `axis` (0 u, 1 v, 2 w) equals `at`,
// the other two coordinates (in increasing axis order) lie in [a0, a1] x [b0, b1]. The surface
// normal is +/- the axis direction (normal_sign); it faces the side the surface is seen from.
// No default member values on purpose: arrays of them sit on the intersector's stack for
// every ray and must cost nothing to declare.
struct FacadeRect {
    double at, a0, a1, b0, b1;
    uint8_t axis;
    int8_t normal_sign;
    FacadeSurface surface;
};

constexpr int kMaxCellRects = 32;
constexpr int kMaxMarginRects = 4;

// A cell's rectangles come in layers ordered by w: balcony (w <= 0), facade plane (w = 0),
// reveals (0 <= w <= recess), pane and room front (w = recess), room (w >= recess). A ray
// moving in +w meets the layers in this order (and in reverse moving in -w), so the intersector
// can stop after the first layer it hits.
constexpr int kCellLayers = 5;

// The opening of one cell in wall coordinates (window, balcony door or shop window by the
// cell's kind): where the reveals start and the pane sits at the bottom of the recess.
CellRect cell_opening(const WallLayout& layout, int floor, int slot);

// The rectangles of one cell (all inside the cell's u, v rectangle), layer after layer.
// Returns the count; layer_end (optional, kCellLayers entries) receives where each layer ends.
int cell_rects(const WallLayout& layout, int floor, int slot, FacadeRect* out, int* layer_end = nullptr);
// The plain facade outside the cell grid (or the whole wall when plain). Returns the count.
int margin_rects(const WallLayout& layout, FacadeRect* out);

// Wall-local frame in world space: world = origin + u * u_axis + v * v_axis + w * w_axis.
struct WallFrame {
    Vec3 origin;
    Vec3 u_axis{1, 0, 0}, v_axis{0, 1, 0}, w_axis{0, 0, 1};

    Vec3 to_world(double u, double v, double w) const {
        return origin + u_axis * u + v_axis * v + w_axis * w;
    }
    Vec3 point_to_local(Vec3 p) const {
        Vec3 d = p - origin;
        return {dot(d, u_axis), dot(d, v_axis), dot(d, w_axis)};
    }
    Vec3 direction_to_local(Vec3 d) const { return {dot(d, u_axis), dot(d, v_axis), dot(d, w_axis)}; }
    Vec3 direction_to_world(Vec3 d) const { return u_axis * d.x + v_axis * d.y + w_axis * d.z; }
};

// The frame of the wall from a to b (a footprint edge) standing on z = bottom_z: u along a->b,
// v up, w to the left of a->b, i.e. into the building for CCW outer rings and CW holes.
WallFrame wall_frame(Vec2 a, Vec2 b, double bottom_z);
// The same frame from its origin (a at bottom_z) and the unit direction a->b.
inline WallFrame wall_frame(Vec3 origin, Vec2 along) {
    WallFrame frame;
    frame.origin = origin;
    frame.u_axis = {along.x, along.y, 0};
    frame.v_axis = {0, 0, 1};
    frame.w_axis = {-along.y, along.x, 0};  // perp_left(along)
    return frame;
}

// Walls of a building: outer ring edges, then every hole's edges.
size_t building_wall_count(const Building& building);

// A building's walls, each ring's orientation found once (O(n)) so that each wall then costs
// O(1) for up to kInlineRings rings and O(log rings) beyond: loops over a building's walls make
// one of these. It refers to the building, which must not change while it is used.
class BuildingWalls {
public:
    explicit BuildingWalls(const Building& building);
    size_t count() const { return count_; }
    // Endpoints of wall `index` (edge from a to b), the building on its left (outer rings walked
    // counter-clockwise, holes clockwise, whatever their orientation in the file).
    void wall(size_t index, Vec2* a, Vec2* b) const;
    // The rules' input for wall `index`.
    WallInput input(size_t index) const;

    // Rings (the outer one and the holes) kept without the heap: the night lights build one per
    // wall they look up. Beyond, the rings' first walls and orientations are kept in vectors.
    static constexpr size_t kInlineRings = 64;

private:
    const Building& building_;
    size_t count_;
    FacadeStyle style_;  // one per building: its type's string compared once, not per wall
    // Orientation of ring r (0: the outer ring, h + 1: hole h), bit r, when there are at most
    // kInlineRings rings; else ring_ccw_[r].
    uint64_t counter_clockwise_ = 0;
    // With more than kInlineRings rings: ring r's first wall index (one more entry: count_).
    std::vector<size_t> ring_first_;
    std::vector<uint8_t> ring_ccw_;
    bool counter_clockwise(size_t ring) const;
    // The ring holding wall `index` (0: the outer ring, h + 1: hole h) and its first wall.
    const Ring& ring_of(size_t index, size_t* ring, size_t* first) const;
};

// One wall without a BuildingWalls (each call finds the rings' orientation again).
void building_wall(const Building& building, size_t index, Vec2* a, Vec2* b);
WallInput building_wall_input(const Building& building, size_t index);

}  // namespace citygen
