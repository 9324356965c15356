#include "render/facade/building_looks.h"

#include <array>

#include <cmath>

#include "common/rng.h"

namespace citygen {

namespace {

// A number in [0, 1) per integer cell.
double cell_unit(int64_t a, int64_t b, uint64_t salt) {
    return hash_to_unit(hash_keys(salt, static_cast<uint64_t>(a), static_cast<uint64_t>(b)));
}

}  // namespace

// The cell numbers last looked up: a bump's four samples 3 mm apart (and the material's at their
// centre) nearly always fall in the same noise cells and the same brick, and hashing the cells is
// most of a pattern's cost. Gives exactly cell_unit's numbers.
class CellUnits {
public:
    // The numbers of cells (iu, iv), (iu + 1, iv), (iu, iv + 1) and (iu + 1, iv + 1).
    struct Quad {
        int64_t iu = 0, iv = 0;
        uint64_t salt = kEmpty;
        double a = 0, b = 0, c = 0, d = 0;
    };
    const Quad& quad(int64_t iu, int64_t iv, uint64_t salt) {
        // The two noises of a pattern have salts of either parity.
        Quad& q = quads_[salt & 1];
        if (q.salt != salt || q.iu != iu || q.iv != iv)
            q = {iu, iv, salt, cell_unit(iu, iv, salt), cell_unit(iu + 1, iv, salt), cell_unit(iu, iv + 1, salt),
                 cell_unit(iu + 1, iv + 1, salt)};
        return q;
    }
    double unit(int64_t a, int64_t b, uint64_t salt) {
        if (unit_.salt != salt || unit_.iu != a || unit_.iv != b) unit_ = {a, b, salt, cell_unit(a, b, salt)};
        return unit_.a;
    }

private:
    static constexpr uint64_t kEmpty = ~0ull;  // no pattern's salt
    Quad quads_[2];
    Quad unit_;  // its a alone
};

namespace {

double srgb_to_linear(double c) { return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4); }

// Smooth value noise in [0, 1): bilinear between cell corners.
double value_noise(double u, double v, uint64_t salt, CellUnits& cells) {
    const double fu = std::floor(u), fv = std::floor(v);
    const int64_t iu = static_cast<int64_t>(fu), iv = static_cast<int64_t>(fv);
    double su = u - fu, sv = v - fv;
    su = su * su * (3 - 2 * su);
    sv = sv * sv * (3 - 2 * sv);
    const CellUnits::Quad& q = cells.quad(iu, iv, salt);
    return (q.a * (1 - su) + q.b * su) * (1 - sv) + (q.c * (1 - su) + q.d * su) * sv;
}

// Running bond (bricks, stones, tiles): units of size w x h, every other row shifted by half;
// `joint` wide joints get `joint_factor`, each unit its own shade within +-variation.
double bond(double u, double v, double w, double h, double joint, double joint_factor, double variation,
            uint64_t salt, CellUnits& cells) {
    const double row = std::floor(v / h);
    const double shifted = u / w + 0.5 * (static_cast<int64_t>(row) & 1);
    const double col = std::floor(shifted);
    const double du = (shifted - col) * w, dv = v - row * h;
    if (du < joint || dv < joint) return joint_factor;
    return 1 + variation * (2 * cells.unit(static_cast<int64_t>(col), static_cast<int64_t>(row), salt) - 1);
}

double wall_pattern(WallMaterial material, double u, double v, CellUnits& cells) {
    switch (material) {
        case WallMaterial::Plaster:
            return 0.96 + 0.05 * value_noise(u / 0.9, v / 0.9, 11, cells) +
                   0.03 * value_noise(u / 0.12, v / 0.12, 12, cells);
        case WallMaterial::Brick: return bond(u, v, 0.25, 0.075, 0.012, 1.45, 0.12, 13, cells);
        case WallMaterial::Concrete:
            return bond(u, v, 3.0, 1.5, 0.02, 0.7, 0.05, 14, cells) *
                   (0.97 + 0.05 * value_noise(u / 0.4, v / 0.4, 15, cells));
        case WallMaterial::Stone: return bond(u, v, 0.6, 0.35, 0.015, 1.25, 0.1, 16, cells);
        case WallMaterial::Wood: {
            const double board = u / 0.15;
            const double f = board - std::floor(board);
            if (f < 0.06) return 0.55;
            return 1 + 0.1 * (2 * cells.unit(static_cast<int64_t>(std::floor(board)), 0, 17) - 1);
        }
        case WallMaterial::Metal: return 0.9 + 0.1 * std::sin(2 * kPi * u / 0.1);
        case WallMaterial::Glass: return 1;
    }
    return 1;
}

double roof_pattern(RoofMaterial material, double u, double v, CellUnits& cells) {
    switch (material) {
        case RoofMaterial::RoofTiles: {
            // Rows up the slope; the lower edge of each row throws a thin shadow on the next one.
            const double row = v / 0.32;
            const double f = row - std::floor(row);
            const double shade = f < 0.1 ? 0.65 : 1.0;
            return shade * bond(u, v, 0.22, 0.32, 0.01, 0.8, 0.1, 21, cells);
        }
        case RoofMaterial::Slate: return bond(u, v, 0.3, 0.2, 0.008, 0.7, 0.08, 22, cells);
        case RoofMaterial::Metal:
        case RoofMaterial::Copper: {
            const double f = u / 0.5 - std::floor(u / 0.5);
            return f < 0.05 ? 0.75 : 1.0;
        }
        case RoofMaterial::TarPaper:
        case RoofMaterial::Concrete:
        case RoofMaterial::Grass:
        case RoofMaterial::Thatch:
            return 0.92 + 0.12 * value_noise(u / 1.5, v / 1.5, 23, cells) +
                   0.05 * value_noise(u / 0.2, v / 0.2, 24, cells);
        case RoofMaterial::Glass: return 1;
    }
    return 1;
}

}  // namespace

Color albedo_from_srgb(uint32_t rgb) {
    static const std::array<double, 256> linear = [] {
        std::array<double, 256> table;
        for (int i = 0; i < 256; ++i) table[i] = srgb_to_linear(i / 255.0);
        return table;
    }();
    return Color{linear[(rgb >> 16) & 0xff], linear[(rgb >> 8) & 0xff], linear[rgb & 0xff]} * 0.8;
}

double wall_pattern(WallMaterial material, double u, double v) {
    CellUnits cells;
    return wall_pattern(material, u, v, cells);
}

double roof_pattern(RoofMaterial material, double u, double v) {
    CellUnits cells;
    return roof_pattern(material, u, v, cells);
}

BuildingLooks::BuildingLooks(const Scene& scene) {
    looks_.reserve(scene.buildings.size());
    for (const Building& b : scene.buildings) {
        looks_.push_back({b.wall_colour, b.roof_colour, b.wall_material, b.roof_material});
    }
}

namespace {

// Wall or roof coordinates at a hit: u, v in metres and the world directions they grow along.
struct SurfaceFrame {
    double u, v;
    Vec3 du, dv;
};
SurfaceFrame surface_frame(const Hit& hit, bool wall) {
    const Vec3 n = hit.geometric_normal, p = hit.position;
    SurfaceFrame f;
    if (wall) {
        const Vec2 along = std::fabs(n.z) < 0.9 ? normalize(Vec2{-n.y, n.x}) : Vec2{1, 0};
        f.du = {along.x, along.y, 0};
        f.dv = std::fabs(n.z) < 0.9 ? Vec3{0, 0, 1} : Vec3{0, 1, 0};
    } else {
        Vec3 eaves = cross(Vec3{0, 0, 1}, n);
        if (length(eaves) < 1e-6) eaves = {1, 0, 0};
        f.du = normalize(eaves);
        f.dv = normalize(cross(n, f.du));
    }
    f.u = dot(p, f.du);
    f.v = dot(p, f.dv);
    return f;
}

// How deep the relief of a pattern is per unit of pattern factor (mortar and joints are recessed
// whether they are lighter or darker than the face).
double relief(WallMaterial m) { return m == WallMaterial::Brick || m == WallMaterial::Stone ? -0.004 : 0.004; }
constexpr double kRoofRelief = 0.006;

}  // namespace

Material BuildingLooks::bumped_material(const MaterialTable& table, Hit& hit) const {
    CellUnits cells;
    bump(hit, cells);
    return material_for(table, hit, cells);
}

void BuildingLooks::bump(Hit& hit, CellUnits& cells) const {
    if (hit.kind != ObjectKind::Building || hit.object >= looks_.size()) return;
    const Look& look = looks_[hit.object];
    const bool wall = hit.material == kFacade && look.has_wall() && look.wall_material != WallMaterial::Glass &&
                      !(textures_ && textures_->has(look.wall_material));
    const bool roof = hit.material == kRoof && look.has_roof() && !(textures_ && textures_->has(look.roof_material));
    if (!wall && !roof) return;
    const SurfaceFrame f = surface_frame(hit, wall);
    // Height field h = relief x pattern; its slope by central differences over 3 mm.
    const double e = 0.003;
    auto h = [&](double u, double v) {
        return wall ? relief(look.wall_material) * wall_pattern(look.wall_material, u, v, cells)
                    : kRoofRelief * roof_pattern(look.roof_material, u, v, cells);
    };
    const double dhdu = (h(f.u + e, f.v) - h(f.u - e, f.v)) / (2 * e);
    const double dhdv = (h(f.u, f.v + e) - h(f.u, f.v - e)) / (2 * e);
    hit.shading_normal = normalize(hit.geometric_normal - f.du * dhdu - f.dv * dhdv);
}

Material BuildingLooks::material_for(const MaterialTable& table, const Hit& hit, CellUnits& cells) const {
    Material m = table[hit.material];
    if (hit.kind != ObjectKind::Building || hit.object >= looks_.size()) return m;
    const Look& look = looks_[hit.object];
    if (hit.material == kFacade && look.has_wall()) {
        const SurfaceFrame f = surface_frame(hit, true);
        m.albedo = textures_ && textures_->has(look.wall_material)
                       ? albedo_from_srgb(look.wall_colour) * textures_->factor(look.wall_material, f.u, f.v, hit.t)
                       : albedo_from_srgb(look.wall_colour) * wall_pattern(look.wall_material, f.u, f.v, cells);
        if (look.wall_material == WallMaterial::Glass) {
            m.type = MaterialType::Glossy;
            m.specular = {0.25, 0.25, 0.25};
            m.exponent = 400;
        }
    } else if (hit.material == kRoof && look.has_roof()) {
        const SurfaceFrame f = surface_frame(hit, false);
        m.albedo = textures_ && textures_->has(look.roof_material)
                       ? albedo_from_srgb(look.roof_colour) * textures_->factor(look.roof_material, f.u, f.v, hit.t)
                       : albedo_from_srgb(look.roof_colour) * roof_pattern(look.roof_material, f.u, f.v, cells);
        if (look.roof_material == RoofMaterial::Metal || look.roof_material == RoofMaterial::Copper ||
            look.roof_material == RoofMaterial::Glass)
            m.specular = {0.08, 0.08, 0.08};
    }
    return m;
}

}  // namespace citygen
