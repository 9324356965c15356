#include "common/scene_info.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <vector>

#include "common/ground.h"

namespace citygen {

namespace {

// Format 1.1: roof shapes (and how many were inferred), height rules, wall materials.
void print_building_looks(const Scene& s, std::FILE* out) {
    std::map<std::string, size_t> roofs, rules, walls;
    size_t inferred = 0, faces = 0, generated = 0;
    for (const Building& b : s.buildings) {
        ++roofs[to_string(b.roof_shape)];
        ++rules[to_string(b.height_rule)];
        ++walls[to_string(b.wall_material)];
        inferred += b.roof_inferred;
        faces += b.roof_faces.size();
        generated += b.generated;
    }
    std::fprintf(out, "generated_buildings: %zu\n", generated);
    auto list = [&](const char* name, const std::map<std::string, size_t>& m) {
        std::fprintf(out, "%s:", name);
        for (const auto& [k, v] : m) std::fprintf(out, " %s %zu,", k.c_str(), v);
        std::fprintf(out, "\n");
    };
    list("roof_shapes", roofs);
    std::fprintf(out, "roof_faces: %zu (%zu roofs by the default rules)\n", faces, inferred);
    list("height_rules", rules);
    list("wall_materials", walls);
}

// Where the scene comes from, its frame and seed.
void print_header_info(const Scene& s, const std::string& name, std::FILE* out) {
    const SceneHeader& h = s.header;
    std::fprintf(out, "scene: %s\n", name.c_str());
    std::fprintf(out, "format_version: %u.%u\n", h.format_major, h.format_minor);
    std::fprintf(out, "generator: %s\n", h.generator.c_str());
    std::fprintf(out, "source: %s\n", h.source.c_str());
    std::fprintf(out, "origin: %.7f, %.7f (lat, lon; %s)\n", h.origin_lat, h.origin_lon,
                 h.projection.c_str());
    std::fprintf(out, "bounds: [%.1f, %.1f] - [%.1f, %.1f] m (%.0f x %.0f m)\n", h.bounds_min.x,
                 h.bounds_min.y, h.bounds_max.x, h.bounds_max.y, h.bounds_max.x - h.bounds_min.x,
                 h.bounds_max.y - h.bounds_min.y);
    std::fprintf(out, "seed: %llu\n", static_cast<unsigned long long>(h.seed));
}

void print_buildings_info(const Scene& s, std::FILE* out) {
    size_t holes = 0, parts = 0, tagged_heights = 0;
    for (const Building& b : s.buildings) {
        holes += b.holes.size();
        parts += b.is_part;
        tagged_heights += b.height_source != HeightSource::Random;
    }
    std::fprintf(out, "buildings: %zu\n", s.buildings.size());
    std::fprintf(out, "building_parts: %zu\n", parts);
    std::fprintf(out, "building_holes: %zu\n", holes);
    std::fprintf(out, "buildings_with_tagged_height: %zu\n", tagged_heights);
    if (!s.buildings.empty()) {
        std::vector<double> heights;
        size_t from_tag = 0, from_levels = 0, vertices = 0;
        for (const Building& b : s.buildings) {
            heights.push_back(b.height);
            from_tag += b.height_source == HeightSource::Tagged;
            from_levels += b.height_source == HeightSource::Levels;
            vertices += b.outer.size();
            for (const Ring& hole : b.holes) vertices += hole.size();
        }
        std::sort(heights.begin(), heights.end());
        std::fprintf(out, "building_heights: %.1f - %.1f m, median %.1f m (%zu from height, %zu from levels, %zu random)\n",
                     heights.front(), heights.back(), heights[heights.size() / 2], from_tag, from_levels,
                     s.buildings.size() - from_tag - from_levels);
        std::fprintf(out, "building_vertices: %zu\n", vertices);
        print_building_looks(s, out);
    }
}

// Roads, joints, sidewalks and lamps.
void print_streets_info(const Scene& s, std::FILE* out) {
    std::fprintf(out, "roads: %zu\n", s.roads.size());
    std::map<std::string, size_t> per_class;
    for (const RoadEdge& r : s.roads) ++per_class[to_string(r.road_class)];
    for (const auto& [c, n] : per_class) std::fprintf(out, "roads_%s: %zu\n", c.c_str(), n);
    std::fprintf(out, "joints: %zu\n", s.joints.size());
    size_t corners = 0;
    for (const Sidewalk& w : s.sidewalks) corners += w.kind == SidewalkKind::Corner;
    std::fprintf(out, "sidewalks: %zu (%zu strips, %zu corners)\n", s.sidewalks.size(),
                 s.sidewalks.size() - corners, corners);
    size_t generated = 0;
    for (const Lamp& l : s.lamps) generated += l.source == LampSource::Generated;
    std::fprintf(out, "lamps: %zu (%zu tagged, %zu generated)\n", s.lamps.size(),
                 s.lamps.size() - generated, generated);
}

// Format 1.1: land cover by class (polygons and square metres) and trees by source.
void print_land_cover_info(const Scene& s, std::FILE* out) {
    std::fprintf(out, "land_cover: %zu\n", s.land_cover.size());
    size_t count[kLandCoverClassCount] = {}, holes = 0;
    double area[kLandCoverClassCount] = {};
    for (const LandCover& c : s.land_cover) {
        const int k = static_cast<int>(c.cover);
        ++count[k];
        area[k] += std::fabs(signed_area(c.outer));
        for (const Ring& hole : c.holes) area[k] -= std::fabs(signed_area(hole));
        holes += c.holes.size();
    }
    for (int k = 0; k < kLandCoverClassCount; ++k)
        if (count[k])
            std::fprintf(out, "land_cover_%s: %zu (%.0f m2)\n", to_string(static_cast<LandCoverClass>(k)),
                         count[k], area[k]);
    std::fprintf(out, "land_cover_holes: %zu\n", holes);
}

// Trees by source, paths and rails by class, crossings and markings.
void print_map_details_info(const Scene& s, std::FILE* out) {
    size_t by_source[3] = {};
    for (const Tree& t : s.trees) ++by_source[static_cast<int>(t.source)];
    std::fprintf(out, "trees: %zu (%zu mapped, %zu in rows, %zu scattered)\n", s.trees.size(), by_source[0],
                 by_source[1], by_source[2]);
    size_t per_class[kPathClassCount] = {}, mapped_sidewalks = 0;
    for (const PathEdge& p : s.paths) {
        ++per_class[static_cast<int>(p.path_class)];
        mapped_sidewalks += p.sidewalk;
    }
    std::fprintf(out, "paths: %zu (%zu mapped sidewalks)\n", s.paths.size(), mapped_sidewalks);
    for (int k = 0; k < kPathClassCount; ++k)
        if (per_class[k]) std::fprintf(out, "paths_%s: %zu\n", to_string(static_cast<PathClass>(k)), per_class[k]);
    std::fprintf(out, "path_joints: %zu\n", s.path_joints.size());
    size_t zebras = 0, marked = 0;
    for (const Crossing& c : s.crossings) zebras += c.kind == CrossingKind::Zebra;
    for (const RoadEdge& r : s.roads) marked += r.centre_line != CentreLine::None || r.edge_lines;
    std::fprintf(out, "crossings: %zu (%zu zebra, %zu stop lines)\n", s.crossings.size(), zebras,
                 s.crossings.size() - zebras);
    std::fprintf(out, "roads_with_markings: %zu\n", marked);
}

double percentile(std::vector<double> v, double p) {
    if (v.empty()) return 0;
    const size_t k = std::min(v.size() - 1, static_cast<size_t>(p / 100 * v.size()));
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(k), v.end());
    return v[k];
}

// How the roads lie on the field (docs/terrain.md, "Fitted to roads and water"): every 2 m
// along each centreline, away from its ends (a joint warps a road's end to meet the others),
// the slope across the carriageway and the grade along it, on the drawn ground. Bridges lie on
// their decks (common/bridge_deck.h), level across and straight along by construction.
void print_road_fit_info(const Scene& s, std::FILE* out) {
    constexpr double kStep = 2;
    std::vector<double> cross, grade;
    for (const RoadEdge& r : s.roads) {
        if (r.bridge) continue;
        const std::vector<Vec2>& line = r.centreline;
        double along = 0, total = 0;
        for (size_t k = 0; k + 1 < line.size(); ++k) total += length(line[k + 1] - line[k]);
        double previous = NAN;
        for (size_t k = 0; k + 1 < line.size(); ++k) {
            const Vec2 a = line[k], d = line[k + 1] - line[k];
            const double l = length(d);
            if (!(l > 0)) continue;
            const Vec2 u = d * (1 / l), n{-u.y, u.x};
            for (double t = std::fmod(kStep - std::fmod(along, kStep), kStep); t < l; t += kStep) {
                const Vec2 p = a + u * t;
                const double at = along + t;
                if (at < r.width || at > total - r.width) continue;
                const double z = ground_height(s, p.x, p.y);
                const Vec2 left = p + n * (r.width / 2), right = p - n * (r.width / 2);
                cross.push_back(std::fabs(ground_height(s, left.x, left.y) - ground_height(s, right.x, right.y)) / r.width);
                if (std::isfinite(previous)) grade.push_back(std::fabs(z - previous) / kStep);
                previous = z;
            }
            along += l;
        }
    }
    if (cross.empty()) return;
    std::fprintf(out, "terrain_road_cross_slope: p50 %.2f%%, p99 %.2f%%, max %.1f%% (%zu points, 2 m apart)\n",
                 100 * percentile(cross, 50), 100 * percentile(cross, 99), 100 * *std::max_element(cross.begin(), cross.end()),
                 cross.size());
    if (!grade.empty())
        std::fprintf(out, "terrain_road_grade: p50 %.1f%%, p99 %.1f%%, max %.1f%%\n", 100 * percentile(grade, 50),
                     100 * percentile(grade, 99), 100 * *std::max_element(grade.begin(), grade.end()));
}

// Format 1.2: the height field's extent, resolution, nodes and height range, when present.
void print_terrain_info(const Scene& s, std::FILE* out) {
    const HeightField& t = s.terrain;
    if (t.empty()) {
        std::fprintf(out, "terrain: none (flat)\n");
        return;
    }
    const Vec2 far = t.origin + Vec2((t.nx - 1) * t.cell, (t.ny - 1) * t.cell);
    std::fprintf(out, "terrain: [%.1f, %.1f] - [%.1f, %.1f] m (%.0f x %.0f m), cell %g m, %u x %u nodes (%zu)\n",
                 t.origin.x, t.origin.y, far.x, far.y, far.x - t.origin.x, far.y - t.origin.y, t.cell, t.nx, t.ny,
                 t.heights.size());
    const auto [lowest, highest] = std::minmax_element(t.heights.begin(), t.heights.end());
    std::fprintf(out, "terrain_heights: %.1f - %.1f m above %s (z = altitude - %.1f m)\n",
                 t.reference_altitude + *lowest, t.reference_altitude + *highest, t.vertical_datum.c_str(),
                 t.reference_altitude);
    print_road_fit_info(s, out);
    size_t tagged = 0;
    double metres = 0;
    for (const RetainingWall& w : s.retaining_walls) {
        tagged += w.height_tagged;
        for (size_t k = 0; k + 1 < w.line.size(); ++k) metres += length(w.line[k + 1] - w.line[k]);
    }
    std::fprintf(out, "retaining_walls: %zu (%zu with a tagged height), %.0f m long\n", s.retaining_walls.size(), tagged,
                 metres);
}

}  // namespace

void print_scene_info(const Scene& s, const std::string& name, std::FILE* out) {
    print_header_info(s, name, out);
    print_buildings_info(s, out);
    print_streets_info(s, out);
    print_land_cover_info(s, out);
    print_map_details_info(s, out);
    std::fprintf(out, "ground: [%.1f, %.1f] - [%.1f, %.1f] m at z=%.2f\n", s.ground.min.x,
                 s.ground.min.y, s.ground.max.x, s.ground.max.y, s.ground.z);
    print_terrain_info(s, out);
    std::fprintf(out, "options:\n");
    for (const auto& [k, v] : s.header.options) std::fprintf(out, "  %s = %s\n", k.c_str(), v.c_str());
}

}  // namespace citygen
