#include "render/facade/facade.h"

#include <algorithm>
#include <cmath>

#include "common/rng.h"

namespace citygen {

const char* to_string(FacadeSurface surface) {
    switch (surface) {
        case FacadeSurface::Wall: return "wall";
        case FacadeSurface::Reveal: return "reveal";
        case FacadeSurface::Glass: return "glass";
        case FacadeSurface::Room: return "room";
        case FacadeSurface::BalconySlab: return "balcony_slab";
        case FacadeSurface::Fence: return "fence";
        case FacadeSurface::BalconyDoor: return "balcony_door";
        case FacadeSurface::ShopWindow: return "shop_window";
    }
    return "unknown";
}

uint64_t facade_building_key(const Building& building) {
    return hash_keys(static_cast<uint64_t>(building.osm.type), static_cast<uint64_t>(building.osm.id));
}

namespace {

// Salts that keep the independent random choices apart.
enum Salt : uint64_t {
    kFloorHeight = 1, kBottomMargin, kTopMargin, kEdgeMargin, kSlotWidth, kWindowWidth,
    kWindowHeight, kSill, kRecess, kRoomDepth, kHasBalconies, kBalconyDepth, kBalconyEvery,
    kDoorWidth, kShop, kWallBalconies
};

// Sizes (metres) that make a facade look like one.
constexpr double kMinFloorHeight = 2.4;
constexpr double kMinSlotWidth = 1.6;
constexpr double kMinRoomDepth = 0.2;  // even at the sharpest corner a window shows some room

}  // namespace

FacadeChoices facade_choices(const FacadeOptions& options, uint64_t building_key, FacadeStyle style) {
    auto dice = [&](Salt salt) { return hash_to_unit(hash_keys(options.seed, building_key, salt)); };
    FacadeChoices c;
    c.style = style;
    c.bottom_margin = 0.3 + 0.3 * dice(kBottomMargin);
    c.top_margin = 0.4 + 0.6 * dice(kTopMargin);
    c.edge_margin = 0.4 + 0.6 * dice(kEdgeMargin);
    // Storeys: houses low, offices and shops tall, the rest in between (tagged levels win).
    const bool offices = style == FacadeStyle::Office || style == FacadeStyle::CurtainWall;
    c.floor_target = style == FacadeStyle::House ? 2.7 + 0.3 * dice(kFloorHeight)
                     : offices                   ? 3.4 + 0.5 * dice(kFloorHeight)
                                                 : 2.9 + 0.5 * dice(kFloorHeight);
    // Window rhythm: offices in narrow, even bays (ribbon windows), houses in wide ones.
    c.slot_target = style == FacadeStyle::Office  ? 1.8 + 0.4 * dice(kSlotWidth)
                    : style == FacadeStyle::House ? 2.8 + 1.2 * dice(kSlotWidth)
                                                  : 2.4 + 1.4 * dice(kSlotWidth);
    c.recess = 0.12 + 0.13 * dice(kRecess);
    c.room_depth = 1.8 + 0.8 * dice(kRoomDepth);
    c.window_width = 1.0 + 0.6 * dice(kWindowWidth);
    c.sill = 0.8 + 0.2 * dice(kSill);
    c.window_height = 1.3 + 0.4 * dice(kWindowHeight);
    c.ribbon = 1.6 + 0.3 * dice(kWindowHeight);
    // Balconies: per building (then only on some of its walls), never on curtain walls or offices.
    const bool no_balconies = style == FacadeStyle::CurtainWall || style == FacadeStyle::Office;
    c.balconies = !no_balconies && dice(kHasBalconies) < 0.4;
    c.balcony_every = dice(kBalconyEvery) < 0.5 ? 1 : 2;
    c.balcony_depth = 1.0 + 0.4 * dice(kBalconyDepth);
    c.door_width = 0.9 + 0.3 * dice(kDoorWidth);
    // Shop front: a row of large panes on the ground floor, where a wall allows one.
    const double shop_probability = style == FacadeStyle::Shops   ? 1.0
                                    : style == FacadeStyle::House ? 0.0
                                                                  : options.shop_probability;
    c.shop = dice(kShop) < shop_probability;
    return c;
}

WallGrid wall_grid(const FacadeOptions& options, const FacadeChoices& c, const WallInput& wall) {
    WallGrid grid;
    if (!(wall.length > 0) || !(wall.height > 0) || c.style == FacadeStyle::Plain) return grid;
    double floor_target = c.floor_target;
    if (wall.levels > 0) {
        double tagged = wall.height / wall.levels;
        if (tagged >= kMinFloorHeight && tagged <= 5.0) floor_target = tagged;
    }
    const double usable_height = wall.height - c.bottom_margin - c.top_margin;
    const double usable_length = wall.length - 2 * c.edge_margin;
    // Clamped before the conversion: a float beyond int's range does not convert (scenes bound
    // walls far below this anyway, see scene_limits.h).
    constexpr double kMaxCells = 1e6;
    const int floors = static_cast<int>(std::clamp(std::floor(usable_height / floor_target), 0.0, kMaxCells));
    const int slots = static_cast<int>(std::clamp(std::floor(usable_length / c.slot_target), 0.0, kMaxCells));
    if (floors < 1 || slots < 1) return grid;
    const double floor_height = usable_height / floors;
    const double slot_width = usable_length / slots;
    if (floor_height < kMinFloorHeight || slot_width < kMinSlotWidth) return grid;
    grid.floors = floors;
    grid.slots = slots;
    grid.slot_width = slot_width;
    grid.floor_height = floor_height;
    grid.room_depth = c.room_depth;
    // At an acute corner the neighbouring wall runs in behind the end cells at w = u * tan(angle):
    // keep the room boxes (which start edge_margin + inset from the corner) in front of it.
    const double corner = std::min(wall.start_angle, wall.end_angle);
    if (corner < 0.5 * kPi) {
        const double deepest = 0.9 * (c.edge_margin + WallLayout::kRoomInset) * std::tan(corner);  // 10% to spare
        grid.room_depth = std::clamp(deepest - c.recess, kMinRoomDepth, grid.room_depth);
    }
    // Never on one-floor walls.
    grid.balconies = c.balconies && floors >= 2 &&
                     hash_to_unit(hash_keys(options.seed, wall.building_key, wall.wall_index, kWallBalconies)) < 0.7;
    // Only on buildings that stand on the ground, behind a tall enough ground floor.
    grid.shop = c.shop && wall.bottom_z < 0.5 && floor_height >= 2.8;
    return grid;
}

WallLayout wall_layout(const FacadeChoices& c, const WallGrid& grid, double length, double height) {
    WallLayout layout;
    layout.length = length;
    layout.height = height;
    if (grid.plain()) return layout;
    const double slot_width = grid.slot_width, floor_height = grid.floor_height;
    layout.floors = grid.floors;
    layout.slots = grid.slots;
    layout.grid_u0 = c.edge_margin;
    layout.grid_v0 = c.bottom_margin;
    layout.slot_width = slot_width;
    layout.floor_height = floor_height;
    layout.recess = c.recess;
    layout.room_depth = grid.room_depth;
    // The window of a slot: centred, at least 0.25 m of wall either side and 0.35 m above; ribbon
    // windows on offices, glass from floor to floor on curtain walls.
    const double window_width = std::min(c.window_width, slot_width - 0.5);
    const double sill = std::min(c.sill, floor_height - 1.2);
    const double window_height = std::min(c.window_height, floor_height - 0.35 - sill);
    layout.window = {0.5 * (slot_width - window_width), 0.5 * (slot_width + window_width), sill, sill + window_height};
    if (c.style == FacadeStyle::Office) {  // nearly the whole bay, a band of wall between
        const double ribbon = std::min(c.ribbon, floor_height - 1.2);
        layout.window = {0.08, slot_width - 0.08, 0.9, 0.9 + ribbon};
    }
    if (c.style == FacadeStyle::CurtainWall) {  // slim mullions
        layout.window = {0.06, slot_width - 0.06, 0.08, floor_height - 0.08};
        layout.recess = 0.06;
    }
    if (grid.balconies) {
        layout.balconies = true;
        layout.balcony_every = c.balcony_every;
        layout.balcony_depth = c.balcony_depth;
        const double door_width = std::min(c.door_width, slot_width - 0.5);
        const double door_top = std::min(WallLayout::kSlabThickness + 2.1, floor_height - 0.3);
        layout.door = {0.5 * (slot_width - door_width), 0.5 * (slot_width + door_width), WallLayout::kSlabThickness,
                       door_top};
    }
    layout.shop = grid.shop;
    return layout;
}

WallLayout make_wall_layout(const FacadeOptions& options, const WallInput& wall) {
    const FacadeChoices choices = facade_choices(options, wall.building_key, wall.style);
    return wall_layout(choices, wall_grid(options, choices, wall), wall.length, wall.height);
}

CellKind cell_kind(const WallLayout& layout, int floor, int slot) {
    if (floor == 0 && layout.shop) return CellKind::Shop;
    if (floor >= 1 && layout.balconies && slot % layout.balcony_every == 0) return CellKind::Balcony;
    return CellKind::Window;
}

bool window_lit(const FacadeOptions& options, uint64_t building_key, uint32_t wall_index, const WallLayout& layout,
                int floor, int slot, double lit_share) {
    if (!(lit_share > 0)) return false;
    const double p = cell_kind(layout, floor, slot) == CellKind::Shop ? std::sqrt(lit_share) : lit_share;
    constexpr uint64_t kLitSalt = 0x11717;
    const uint64_t cell = static_cast<uint64_t>(floor) << 32 | static_cast<uint32_t>(slot);
    return hash_to_unit(hash_keys(options.seed, building_key, wall_index, cell, kLitSalt)) < p;
}

namespace {

// Rectangle builders in wall-local (u, v, w). The two free axes are in increasing order:
// u-plane: (v, w); v-plane: (u, w); w-plane: (u, v).
FacadeRect u_plane(double u, double v0, double v1, double w0, double w1, int sign, FacadeSurface s) {
    return {u, v0, v1, w0, w1, 0, static_cast<int8_t>(sign), s};
}
FacadeRect v_plane(double v, double u0, double u1, double w0, double w1, int sign, FacadeSurface s) {
    return {v, u0, u1, w0, w1, 1, static_cast<int8_t>(sign), s};
}
FacadeRect w_plane(double w, double u0, double u1, double v0, double v1, int sign, FacadeSurface s) {
    return {w, u0, u1, v0, v1, 2, static_cast<int8_t>(sign), s};
}

// `outer` minus `hole` (hole strictly inside) as four w-plane rectangles: below, above, left, right.
int frame_around(double w, CellRect outer, CellRect hole, int sign, FacadeSurface s, FacadeRect* out) {
    out[0] = w_plane(w, outer.u0, outer.u1, outer.v0, hole.v0, sign, s);
    out[1] = w_plane(w, outer.u0, outer.u1, hole.v1, outer.v1, sign, s);
    out[2] = w_plane(w, outer.u0, hole.u0, hole.v0, hole.v1, sign, s);
    out[3] = w_plane(w, hole.u1, outer.u1, hole.v0, hole.v1, sign, s);
    return 4;
}

CellRect offset(CellRect r, double du, double dv) { return {r.u0 + du, r.u1 + du, r.v0 + dv, r.v1 + dv}; }

}  // namespace

CellRect cell_opening(const WallLayout& layout, int floor, int slot) {
    const CellKind kind = cell_kind(layout, floor, slot);
    return offset(kind == CellKind::Shop      ? layout.shop_window()
                  : kind == CellKind::Balcony ? layout.door
                                              : layout.window,
                  layout.grid_u0 + slot * layout.slot_width, layout.grid_v0 + floor * layout.floor_height);
}

int cell_rects(const WallLayout& layout, int floor, int slot, FacadeRect* out, int* layer_end) {
    const double cu = layout.grid_u0 + slot * layout.slot_width;
    const double cv = layout.grid_v0 + floor * layout.floor_height;
    const CellRect cell{cu, cu + layout.slot_width, cv, cv + layout.floor_height};
    const CellKind kind = cell_kind(layout, floor, slot);
    const CellRect opening = cell_opening(layout, floor, slot);
    const FacadeSurface pane = kind == CellKind::Shop      ? FacadeSurface::ShopWindow
                               : kind == CellKind::Balcony ? FacadeSurface::BalconyDoor
                                                           : FacadeSurface::Glass;
    const double d = layout.recess;
    const double back = d + layout.room_depth;
    const double inset = WallLayout::kRoomInset;
    const CellRect room{cell.u0 + inset, cell.u1 - inset, cell.v0 + inset, cell.v1 - inset};
    int layer_ends[kCellLayers];
    int n = 0;

    // Layer 0: a slab at the bottom of the cell sticking out of the wall, a railing round its edge.
    if (kind == CellKind::Balcony) {
        const double bu0 = cell.u0 + WallLayout::kBalconyMargin, bu1 = cell.u1 - WallLayout::kBalconyMargin;
        const double front = -layout.balcony_depth;
        const double top = cv + WallLayout::kSlabThickness;
        const double rail = top + layout.fence_height();
        out[n++] = v_plane(top, bu0, bu1, front, 0.0, +1, FacadeSurface::BalconySlab);
        out[n++] = v_plane(cv, bu0, bu1, front, 0.0, -1, FacadeSurface::BalconySlab);
        out[n++] = w_plane(front, bu0, bu1, cv, top, -1, FacadeSurface::BalconySlab);
        out[n++] = u_plane(bu0, cv, top, front, 0.0, -1, FacadeSurface::BalconySlab);
        out[n++] = u_plane(bu1, cv, top, front, 0.0, +1, FacadeSurface::BalconySlab);
        out[n++] = w_plane(front, bu0, bu1, top, rail, -1, FacadeSurface::Fence);
        out[n++] = u_plane(bu0, top, rail, front, 0.0, -1, FacadeSurface::Fence);
        out[n++] = u_plane(bu1, top, rail, front, 0.0, +1, FacadeSurface::Fence);
    }
    layer_ends[0] = n;
    // Layer 1: the facade plane around the opening, seen from outside.
    n += frame_around(0.0, cell, opening, -1, FacadeSurface::Wall, out + n);
    layer_ends[1] = n;
    // Layer 2: reveals, the four sides of the recess, facing into the opening.
    out[n++] = u_plane(opening.u0, opening.v0, opening.v1, 0.0, d, +1, FacadeSurface::Reveal);
    out[n++] = u_plane(opening.u1, opening.v0, opening.v1, 0.0, d, -1, FacadeSurface::Reveal);
    out[n++] = v_plane(opening.v0, opening.u0, opening.u1, 0.0, d, +1, FacadeSurface::Reveal);
    out[n++] = v_plane(opening.v1, opening.u0, opening.u1, 0.0, d, -1, FacadeSurface::Reveal);
    layer_ends[2] = n;
    // Layer 3: the pane at the bottom of the recess, and the room's front wall around it (seen
    // from inside the room, like every room face).
    out[n++] = w_plane(d, opening.u0, opening.u1, opening.v0, opening.v1, -1, pane);
    n += frame_around(d, room, opening, +1, FacadeSurface::Room, out + n);
    layer_ends[3] = n;
    // Layer 4: the rest of the room box behind the pane.
    out[n++] = w_plane(back, room.u0, room.u1, room.v0, room.v1, -1, FacadeSurface::Room);
    out[n++] = u_plane(room.u0, room.v0, room.v1, d, back, +1, FacadeSurface::Room);
    out[n++] = u_plane(room.u1, room.v0, room.v1, d, back, -1, FacadeSurface::Room);
    out[n++] = v_plane(room.v0, room.u0, room.u1, d, back, +1, FacadeSurface::Room);
    out[n++] = v_plane(room.v1, room.u0, room.u1, d, back, -1, FacadeSurface::Room);
    layer_ends[4] = n;
    if (layer_end)
        for (int i = 0; i < kCellLayers; ++i) layer_end[i] = layer_ends[i];
    return n;
}

int margin_rects(const WallLayout& layout, FacadeRect* out) {
    const double L = layout.length, H = layout.height;
    if (layout.plain()) {
        out[0] = w_plane(0.0, 0.0, L, 0.0, H, -1, FacadeSurface::Wall);
        return 1;
    }
    const double u0 = layout.grid_u0, u1 = layout.grid_u1(), v0 = layout.grid_v0, v1 = layout.grid_v1();
    out[0] = w_plane(0.0, 0.0, u0, 0.0, H, -1, FacadeSurface::Wall);   // left edge strip
    out[1] = w_plane(0.0, u1, L, 0.0, H, -1, FacadeSurface::Wall);     // right edge strip
    out[2] = w_plane(0.0, u0, u1, 0.0, v0, -1, FacadeSurface::Wall);   // plinth
    out[3] = w_plane(0.0, u0, u1, v1, H, -1, FacadeSurface::Wall);     // parapet
    return 4;
}

WallFrame wall_frame(Vec2 a, Vec2 b, double bottom_z) { return wall_frame({a.x, a.y, bottom_z}, normalize(b - a)); }

size_t building_wall_count(const Building& building) {
    size_t n = building.outer.size();
    for (const Ring& hole : building.holes) n += hole.size();
    return n;
}

BuildingWalls::BuildingWalls(const Building& building)
    : building_(building), count_(building_wall_count(building)), style_(facade_style(building)) {
    const size_t rings = 1 + building.holes.size();
    auto ring = [&](size_t r) -> const Ring& { return r == 0 ? building.outer : building.holes[r - 1]; };
    if (rings <= kInlineRings) {
        for (size_t r = 0; r < rings; ++r)
            if (signed_area(ring(r)) > 0) counter_clockwise_ |= uint64_t{1} << r;
        return;
    }
    ring_first_.reserve(rings + 1);
    ring_ccw_.reserve(rings);
    size_t first = 0;
    for (size_t r = 0; r < rings; ++r) {
        ring_first_.push_back(first);
        first += ring(r).size();
        ring_ccw_.push_back(signed_area(ring(r)) > 0);
    }
    ring_first_.push_back(first);
}

bool BuildingWalls::counter_clockwise(size_t ring) const {
    if (ring_ccw_.empty()) return (counter_clockwise_ >> ring) & 1;
    return ring_ccw_[ring];
}

const Ring& BuildingWalls::ring_of(size_t index, size_t* ring, size_t* first) const {
    if (!ring_first_.empty()) {
        // The last ring whose first wall is at or before index (empty rings share a first wall).
        const size_t r = static_cast<size_t>(std::upper_bound(ring_first_.begin(), ring_first_.end() - 1, index) -
                                             ring_first_.begin()) - 1;
        *ring = r;
        *first = ring_first_[r];
        return r == 0 ? building_.outer : building_.holes[r - 1];
    }
    const Ring* current = &building_.outer;
    size_t r = 0, start = 0;
    while (index - start >= current->size() && r < building_.holes.size()) {
        start += current->size();
        current = &building_.holes[r++];
    }
    *ring = r;
    *first = start;
    return *current;
}

void BuildingWalls::wall(size_t index, Vec2* a, Vec2* b) const {
    size_t ring_index, first;
    const Ring& ring = ring_of(index, &ring_index, &first);
    index -= first;
    // Walk outer rings counter-clockwise and holes clockwise whatever the file says, so that the
    // building is always on the left (+w) of a wall.
    const size_t n = ring.size();
    if (counter_clockwise(ring_index) == (ring_index == 0)) {
        *a = ring[index];
        *b = ring[(index + 1) % n];
    } else {
        *a = ring[n - 1 - index];
        *b = ring[(2 * n - 2 - index) % n];
    }
}

void building_wall(const Building& building, size_t index, Vec2* a, Vec2* b) {
    BuildingWalls(building).wall(index, a, b);
}

namespace {

// Interior angle at `corner` between the footprint edges to `ahead` and back to `behind`, with
// the building on the left of behind -> corner -> ahead: in (0, 2 pi).
double interior_angle(Vec2 behind, Vec2 corner, Vec2 ahead) {
    const Vec2 out = ahead - corner, back = behind - corner;
    double angle = std::atan2(cross(out, back), dot(out, back));
    if (angle <= 0) angle += 2 * kPi;
    return angle;
}

}  // namespace

WallInput BuildingWalls::input(size_t index) const {
    const Building& building = building_;
    Vec2 a, b;
    wall(index, &a, &b);
    // The neighbours of this wall in the same ring (walls are numbered ring by ring).
    size_t ring, first;
    const size_t count = ring_of(index, &ring, &first).size();
    Vec2 before, unused, after;
    wall(first + (index - first + count - 1) % count, &before, &unused);
    wall(first + (index - first + 1) % count, &unused, &after);
    WallInput result;
    result.building_key = facade_building_key(building);
    result.wall_index = static_cast<uint32_t>(index);
    result.length = length(b - a);
    result.bottom_z = building.min_height;
    result.height = building.eaves_height() - building.min_height;  // gables above are roof faces
    result.levels = building.levels;
    if (a != before) result.start_angle = interior_angle(before, a, b);
    if (b != after) result.end_angle = interior_angle(a, b, after);
    result.style = style_;
    return result;
}

WallInput building_wall_input(const Building& building, size_t index) {
    return BuildingWalls(building).input(index);
}

FacadeStyle facade_style(const Building& b) {
    auto is = [&](std::initializer_list<const char*> types) {
        for (const char* t : types)
            if (b.type == t) return true;
        return false;
    };
    if (is({"garage", "garages", "shed", "carport", "industrial", "warehouse", "hangar", "barn", "farm_auxiliary",
            "storage_tank", "silo", "transformer_tower", "service"}))
        return FacadeStyle::Plain;
    if (b.wall_material == WallMaterial::Glass || (is({"office", "commercial"}) && b.height > 30))
        return FacadeStyle::CurtainWall;
    if (is({"house", "detached", "semidetached_house", "terrace", "bungalow", "villa", "farm"}))
        return FacadeStyle::House;
    if (is({"retail", "supermarket", "kiosk"})) return FacadeStyle::Shops;
    if (is({"office", "commercial", "government", "bank"})) return FacadeStyle::Office;
    return FacadeStyle::Normal;
}

}  // namespace citygen
