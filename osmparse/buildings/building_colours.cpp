#include "osmparse/buildings/building_colours.h"

#include <cstring>
#include <string>

#include "common/rng.h"
#include "osmparse/buildings/parse_colour.h"

namespace citygen {

namespace {
enum Salt : uint64_t { kWallMaterial = 301, kWallColour, kRoofMaterial, kRoofColour };

bool is_one_of(const std::string& value, std::initializer_list<const char*> list) {
    for (const char* s : list)
        if (value == s) return true;
    return false;
}

template <size_t N>
uint32_t pick(const uint32_t (&palette)[N], double u) {
    return palette[std::min(N - 1, static_cast<size_t>(u * N))];
}

// Palettes (sRGB) of real facades and roofs, per material.
const uint32_t kPlaster[] = {0xe8dcc0, 0xe9d8a6, 0xd9b77e, 0xd8a48f, 0xd6d3cc, 0xeeeae2,
                             0xc9d3b4, 0xbfc9cc, 0xe0b8b0, 0xf0e4cc, 0xcfc2a8, 0xb9b1a4};
const uint32_t kBrick[] = {0x9c4a33, 0xa65b3e, 0x8b3f2c, 0xc8a46a, 0x7a3a2a};
const uint32_t kConcrete[] = {0xa9a59e, 0xbdb8ae, 0x8f8c86, 0xc8c4bc};
const uint32_t kStone[] = {0xc2b59b, 0xa89f8d, 0xd1c7b0};
const uint32_t kGlass[] = {0x5e7d8e, 0x4f6a78, 0x6f8a8f};
const uint32_t kWood[] = {0x8a6a48, 0x6e5238, 0xa0825e};
const uint32_t kMetal[] = {0x9ea4a8, 0x8a9296, 0xb4b8b8, 0x7d8a80};
const uint32_t kTiles[] = {0x9a4a32, 0xa8553a, 0x7e3b2a, 0x8c5440, 0x6b3a2e};
const uint32_t kSlate[] = {0x4d5157, 0x5a5e66, 0x44474d};
const uint32_t kRoofMetal[] = {0x6e7a7e, 0x7d8688, 0x5b6a6e};
const uint32_t kCopper[] = {0x6fa58c, 0x5e9a80};
const uint32_t kTarPaper[] = {0x6f6b66, 0x5c5955, 0x7a766f};
const uint32_t kRoofConcrete[] = {0x8a8680, 0x9a968e};
const uint32_t kThatch[] = {0x9a8458};
const uint32_t kGrass[] = {0x5d7a3a};

uint32_t wall_palette(WallMaterial m, double u) {
    switch (m) {
        case WallMaterial::Plaster: return pick(kPlaster, u);
        case WallMaterial::Brick: return pick(kBrick, u);
        case WallMaterial::Concrete: return pick(kConcrete, u);
        case WallMaterial::Stone: return pick(kStone, u);
        case WallMaterial::Glass: return pick(kGlass, u);
        case WallMaterial::Wood: return pick(kWood, u);
        case WallMaterial::Metal: return pick(kMetal, u);
    }
    return kPlaster[0];
}

uint32_t roof_palette(RoofMaterial m, double u) {
    switch (m) {
        case RoofMaterial::RoofTiles: return pick(kTiles, u);
        case RoofMaterial::Slate: return pick(kSlate, u);
        case RoofMaterial::Metal: return pick(kRoofMetal, u);
        case RoofMaterial::Copper: return pick(kCopper, u);
        case RoofMaterial::Concrete: return pick(kRoofConcrete, u);
        case RoofMaterial::TarPaper: return pick(kTarPaper, u);
        case RoofMaterial::Thatch: return pick(kThatch, u);
        case RoofMaterial::Glass: return pick(kGlass, u);
        case RoofMaterial::Grass: return pick(kGrass, u);
    }
    return kTiles[0];
}

WallMaterial default_wall_material(const Building& b, double u) {
    const std::string& t = b.type;
    if (is_one_of(t, {"office", "commercial"}) && b.height > 30) return u < 0.6 ? WallMaterial::Glass : WallMaterial::Concrete;
    if (b.height > 60) return u < 0.5 ? WallMaterial::Glass : WallMaterial::Concrete;
    if (is_one_of(t, {"house", "detached", "semidetached_house", "terrace", "bungalow", "villa"}))
        return u < 0.7 ? WallMaterial::Plaster : WallMaterial::Brick;
    if (is_one_of(t, {"church", "cathedral", "chapel"})) return u < 0.6 ? WallMaterial::Stone : WallMaterial::Brick;
    if (is_one_of(t, {"industrial", "warehouse", "manufacture", "hangar"}))
        return u < 0.5 ? WallMaterial::Metal : WallMaterial::Concrete;
    if (is_one_of(t, {"office", "commercial", "retail", "supermarket", "school", "university", "hospital"}))
        return u < 0.5 ? WallMaterial::Concrete : WallMaterial::Plaster;
    if (is_one_of(t, {"garage", "garages", "carport"})) return u < 0.7 ? WallMaterial::Concrete : WallMaterial::Plaster;
    if (is_one_of(t, {"shed", "hut", "cabin", "barn", "farm_auxiliary", "stable"}))
        return u < 0.6 ? WallMaterial::Wood : WallMaterial::Brick;
    return u < 0.72 ? WallMaterial::Plaster : u < 0.92 ? WallMaterial::Brick : WallMaterial::Concrete;
}

RoofMaterial default_roof_material(const Building& b, double u) {
    if (b.roof_shape == RoofShape::Flat || b.roof_shape == RoofShape::Skillion)
        return u < 0.7 ? RoofMaterial::TarPaper : RoofMaterial::Concrete;
    if (b.roof_shape == RoofShape::Dome || b.roof_shape == RoofShape::Onion)
        return u < 0.5 ? RoofMaterial::Copper : RoofMaterial::Metal;
    return u < 0.75 ? RoofMaterial::RoofTiles : u < 0.9 ? RoofMaterial::Slate : RoofMaterial::Metal;
}

}  // namespace

bool parse_wall_material(const char* text, WallMaterial* m) {
    static const std::pair<const char*, WallMaterial> names[] = {
        {"plaster", WallMaterial::Plaster},   {"render", WallMaterial::Plaster},
        {"brick", WallMaterial::Brick},       {"bricks", WallMaterial::Brick},
        {"concrete", WallMaterial::Concrete}, {"reinforced_concrete", WallMaterial::Concrete},
        {"cement_block", WallMaterial::Concrete}, {"stone", WallMaterial::Stone},
        {"sandstone", WallMaterial::Stone},   {"limestone", WallMaterial::Stone},
        {"glass", WallMaterial::Glass},       {"mirror", WallMaterial::Glass},
        {"wood", WallMaterial::Wood},         {"timber_framing", WallMaterial::Wood},
        {"metal", WallMaterial::Metal},       {"steel", WallMaterial::Metal},
        {"metal_plates", WallMaterial::Metal},
    };
    for (const auto& [name, value] : names)
        if (std::strcmp(text, name) == 0) {
            *m = value;
            return true;
        }
    return false;
}

bool parse_roof_material(const char* text, RoofMaterial* m) {
    static const std::pair<const char*, RoofMaterial> names[] = {
        {"roof_tiles", RoofMaterial::RoofTiles}, {"tile", RoofMaterial::RoofTiles},
        {"tiles", RoofMaterial::RoofTiles},      {"slate", RoofMaterial::Slate},
        {"stone", RoofMaterial::Slate},          {"metal", RoofMaterial::Metal},
        {"metal_sheet", RoofMaterial::Metal},    {"tin", RoofMaterial::Metal},
        {"copper", RoofMaterial::Copper},        {"concrete", RoofMaterial::Concrete},
        {"eternit", RoofMaterial::Concrete},     {"asbestos", RoofMaterial::Concrete},
        {"tar_paper", RoofMaterial::TarPaper},   {"asphalt", RoofMaterial::TarPaper},
        {"gravel", RoofMaterial::TarPaper},      {"thatch", RoofMaterial::Thatch},
        {"glass", RoofMaterial::Glass},          {"grass", RoofMaterial::Grass},
        {"plants", RoofMaterial::Grass},
    };
    for (const auto& [name, value] : names)
        if (std::strcmp(text, name) == 0) {
            *m = value;
            return true;
        }
    return false;
}

void choose_colours_and_materials(std::vector<Building>& buildings, const BuildingTagIndex& index,
                                  const BuildingParams& params, ParseReport& report) {
    for (Building& b : buildings) {
        const OsmTags& tags = index.find(b.osm);
        const uint64_t key = hash_keys(params.seed, static_cast<uint64_t>(b.osm.type), static_cast<uint64_t>(b.osm.id));
        auto unit = [&](Salt salt) { return hash_to_unit(hash_keys(key, salt)); };
        b.colour_inferred = 0;

        const char* wall_text = tags.get("building:material");
        if (!wall_text) wall_text = tags.get("building:facade:material");
        if (!wall_text || !parse_wall_material(wall_text, &b.wall_material)) {
            if (wall_text) report.note(ReportKind::ColoursAndMaterials, ReportReason::UnknownWallMaterial);
            b.wall_material = default_wall_material(b, unit(kWallMaterial));
        }
        const char* roof_text = tags.get("roof:material");
        if (!roof_text || !parse_roof_material(roof_text, &b.roof_material)) {
            if (roof_text) report.note(ReportKind::ColoursAndMaterials, ReportReason::UnknownRoofMaterial);
            b.roof_material = default_roof_material(b, unit(kRoofMaterial));
        }

        uint32_t rgb = 0;
        const char* wall_colour = tags.get("building:colour");
        if (!wall_colour) wall_colour = tags.get("building:facade:colour");
        if (wall_colour && parse_colour(wall_colour, &rgb)) {
            b.wall_colour = 0xff000000u | rgb;
            report.note(ReportKind::ColoursAndMaterials, ReportReason::WallColourTagged);
        } else {
            if (wall_colour) report.note(ReportKind::ColoursAndMaterials, ReportReason::BadWallColour);
            b.wall_colour = 0xff000000u | wall_palette(b.wall_material, unit(kWallColour));
            b.colour_inferred |= kWallColourInferred;
        }
        const char* roof_colour = tags.get("roof:colour");
        if (roof_colour && parse_colour(roof_colour, &rgb)) {
            b.roof_colour = 0xff000000u | rgb;
            report.note(ReportKind::ColoursAndMaterials, ReportReason::RoofColourTagged);
        } else {
            if (roof_colour) report.note(ReportKind::ColoursAndMaterials, ReportReason::BadRoofColour);
            b.roof_colour = 0xff000000u | roof_palette(b.roof_material, unit(kRoofColour));
            b.colour_inferred |= kRoofColourInferred;
        }
    }
}

}  // namespace citygen
