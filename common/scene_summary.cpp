#include "scene_summary.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace citygen {

namespace {

const char* road_class_name(RoadClass c) {
    static const char* names[] = {"motorway", "trunk", "primary", "secondary", "tertiary",
                                  "unclassified", "residential", "living_street", "service", "other"};
    const auto i = static_cast<size_t>(c);
    return i < sizeof names / sizeof *names ? names[i] : "?";
}

// Largest distance between corresponding points, or infinity when the counts differ.
double max_point_distance(const std::vector<Vec2>& a, const std::vector<Vec2>& b) {
    if (a.size() != b.size()) return INFINITY;
    double d = 0;
    for (size_t i = 0; i < a.size(); ++i) d = std::max(d, length(a[i] - b[i]));
    return d;
}

std::string metres(double d) {
    if (!std::isfinite(d)) return "a different number of points";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.3f m", d);
    return buf;
}

// Objects keyed by a stable identity string; repeated identities get #0, #1, ... in file order.
template <typename T, typename KeyFn>
std::map<std::string, const T*> keyed(const std::vector<T>& items, KeyFn key) {
    std::map<std::string, const T*> out;
    std::map<std::string, int> seen;
    for (const T& item : items) {
        const std::string k = key(item);
        out[k + "#" + std::to_string(seen[k]++)] = &item;
    }
    return out;
}

// Compares two keyed collections; `compare` returns "" when equal, else what changed.
template <typename T, typename CompareFn>
void diff_kind(const char* kind, const std::map<std::string, const T*>& a,
               const std::map<std::string, const T*>& b, CompareFn compare,
               std::vector<SceneChange>& out) {
    for (const auto& [k, x] : a) {
        auto it = b.find(k);
        if (it == b.end()) {
            out.push_back({"removed", std::string(kind) + " " + k, ""});
        } else {
            std::string detail = compare(*x, *it->second);
            if (!detail.empty()) out.push_back({"changed", std::string(kind) + " " + k, detail});
        }
    }
    for (const auto& [k, x] : b)
        if (!a.count(k)) out.push_back({"added", std::string(kind) + " " + k, ""});
}

}  // namespace

// Format 1.1: roof shapes (and how many were inferred), height rules, wall materials.
static void print_building_looks(const Scene& s, std::FILE* out) {
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

void print_scene_info(const Scene& s, const std::string& name, std::FILE* out) {
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
    std::fprintf(out, "roads: %zu\n", s.roads.size());
    std::map<std::string, size_t> per_class;
    for (const RoadEdge& r : s.roads) ++per_class[road_class_name(r.road_class)];
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
    // Format 1.1: land cover by class (polygons and square metres) and trees by source.
    std::fprintf(out, "land_cover: %zu\n", s.land_cover.size());
    {
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
    {
        size_t by_source[3] = {};
        for (const Tree& t : s.trees) ++by_source[static_cast<int>(t.source)];
        std::fprintf(out, "trees: %zu (%zu mapped, %zu in rows, %zu scattered)\n", s.trees.size(), by_source[0],
                     by_source[1], by_source[2]);
    }
    {
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
    std::fprintf(out, "ground: [%.1f, %.1f] - [%.1f, %.1f] m at z=%.2f\n", s.ground.min.x,
                 s.ground.min.y, s.ground.max.x, s.ground.max.y, s.ground.z);
    std::fprintf(out, "options:\n");
    for (const auto& [k, v] : h.options) std::fprintf(out, "  %s = %s\n", k.c_str(), v.c_str());
}

std::vector<SceneChange> diff_scenes(const Scene& a, const Scene& b, double tol) {
    std::vector<SceneChange> out;
    if (a.header.format_major != b.header.format_major || a.header.format_minor != b.header.format_minor)
        out.push_back({"changed", "header", "format version differs"});
    if (a.header.options != b.header.options) out.push_back({"changed", "header", "parse options differ"});

    auto building_key = [](const Building& x) { return to_string(x.osm) + (x.is_part ? "/part" : ""); };
    diff_kind("building", keyed(a.buildings, building_key), keyed(b.buildings, building_key),
              [tol](const Building& x, const Building& y) -> std::string {
                  double d = max_point_distance(x.outer, y.outer);
                  if (d > tol) return "outline moved " + metres(d);
                  if (x.holes.size() != y.holes.size()) return "number of holes differs";
                  for (size_t i = 0; i < x.holes.size(); ++i)
                      if ((d = max_point_distance(x.holes[i], y.holes[i])) > tol) return "hole moved " + metres(d);
                  if (std::fabs(x.height - y.height) > tol || std::fabs(x.min_height - y.min_height) > tol)
                      return "height changed by " + metres(std::max(std::fabs(x.height - y.height),
                                                                    std::fabs(x.min_height - y.min_height)));
                  if (x.roof_shape != y.roof_shape)
                      return std::string("roof ") + to_string(x.roof_shape) + " -> " + to_string(y.roof_shape);
                  if (std::fabs(x.roof_height - y.roof_height) > tol)
                      return "roof height changed by " + metres(std::fabs(x.roof_height - y.roof_height));
                  if (x.roof_faces.size() != y.roof_faces.size()) return "number of roof faces differs";
                  for (size_t i = 0; i < x.roof_faces.size(); ++i) {
                      const auto& p = x.roof_faces[i].points;
                      const auto& q = y.roof_faces[i].points;
                      if (p.size() != q.size() || x.roof_faces[i].kind != y.roof_faces[i].kind) return "roof face differs";
                      for (size_t j = 0; j < p.size(); ++j)
                          if ((d = length(p[j] - q[j])) > tol) return "roof face moved " + metres(d);
                  }
                  if (x.wall_colour != y.wall_colour || x.roof_colour != y.roof_colour) return "colour differs";
                  if (x.wall_material != y.wall_material || x.roof_material != y.roof_material)
                      return "material differs";
                  if (x.height_rule != y.height_rule) return "height rule differs";
                  if (x.generated != y.generated) return "generated differs";
                  return "";
              },
              out);

    auto road_key = [](const RoadEdge& x) {
        return to_string(x.osm) + ":" + std::to_string(x.from_node) + "-" + std::to_string(x.to_node);
    };
    diff_kind("road", keyed(a.roads, road_key), keyed(b.roads, road_key),
              [tol](const RoadEdge& x, const RoadEdge& y) -> std::string {
                  double d = max_point_distance(x.quad, y.quad);
                  if (d > tol) return "quadrangle moved " + metres(d);
                  if ((d = max_point_distance(x.centreline, y.centreline)) > tol) return "centreline moved " + metres(d);
                  if (std::fabs(x.width - y.width) > tol) return "width changed by " + metres(std::fabs(x.width - y.width));
                  if (x.sidewalk_left != y.sidewalk_left || x.sidewalk_right != y.sidewalk_right) return "sidewalks differ";
                  if (x.lanes_forward != y.lanes_forward || x.lanes_backward != y.lanes_backward ||
                      x.centre_line != y.centre_line || x.edge_lines != y.edge_lines ||
                      x.cycle_lane_left != y.cycle_lane_left || x.cycle_lane_right != y.cycle_lane_right)
                      return "lanes or markings differ";
                  return "";
              },
              out);

    auto joint_key = [](const Joint& x) { return to_string(x.osm); };
    diff_kind("joint", keyed(a.joints, joint_key), keyed(b.joints, joint_key),
              [tol](const Joint& x, const Joint& y) -> std::string {
                  double d = max_point_distance(x.polygon, y.polygon);
                  return d > tol ? "polygon moved " + metres(d) : "";
              },
              out);

    // Sidewalks are keyed by the OSM identity of the road or joint they belong to.
    auto sidewalk_key = [](const Scene& s) {
        return [&s](const Sidewalk& x) {
            if (x.kind == SidewalkKind::Strip && x.road >= 0) {
                const RoadEdge& r = s.roads[x.road];
                return "strip " + to_string(r.osm) + ":" + std::to_string(r.from_node) + "-" + std::to_string(r.to_node);
            }
            if (x.kind == SidewalkKind::Corner && x.joint >= 0) return "corner " + to_string(s.joints[x.joint].osm);
            return std::string(x.kind == SidewalkKind::Strip ? "strip" : "corner");
        };
    };
    diff_kind("sidewalk", keyed(a.sidewalks, sidewalk_key(a)), keyed(b.sidewalks, sidewalk_key(b)),
              [tol](const Sidewalk& x, const Sidewalk& y) -> std::string {
                  double d = max_point_distance(x.polygon, y.polygon);
                  return d > tol ? "polygon moved " + metres(d) : "";
              },
              out);

    auto lamp_key = [](const Lamp& x) {
        return std::string(x.source == LampSource::Tagged ? "tagged " : "generated ") + to_string(x.osm);
    };
    diff_kind("lamp", keyed(a.lamps, lamp_key), keyed(b.lamps, lamp_key),
              [tol](const Lamp& x, const Lamp& y) -> std::string {
                  double d = length(x.position - y.position);
                  return d > tol ? "moved " + metres(d) : "";
              },
              out);

    auto path_key = [](const PathEdge& x) {
        return to_string(x.osm) + ":" + std::to_string(x.from_node) + "-" + std::to_string(x.to_node);
    };
    diff_kind("path", keyed(a.paths, path_key), keyed(b.paths, path_key),
              [tol](const PathEdge& x, const PathEdge& y) -> std::string {
                  double d = max_point_distance(x.quad, y.quad);
                  if (d > tol) return "quadrangle moved " + metres(d);
                  if (x.path_class != y.path_class) return "class differs";
                  return "";
              },
              out);
    auto path_joint_key = [](const Joint& x) { return to_string(x.osm); };
    diff_kind("path_joint", keyed(a.path_joints, path_joint_key), keyed(b.path_joints, path_joint_key),
              [tol](const Joint& x, const Joint& y) -> std::string {
                  double d = max_point_distance(x.polygon, y.polygon);
                  return d > tol ? "polygon moved " + metres(d) : "";
              },
              out);

    auto crossing_key = [](const Crossing& x) {
        return std::string(x.kind == CrossingKind::Zebra ? "zebra " : "stop line ") + to_string(x.osm);
    };
    diff_kind("crossing", keyed(a.crossings, crossing_key), keyed(b.crossings, crossing_key),
              [tol](const Crossing& x, const Crossing& y) -> std::string {
                  const double d = length(x.position - y.position);
                  return d > tol ? "moved " + metres(d) : "";
              },
              out);

    auto cover_key = [](const LandCover& x) { return std::string(to_string(x.cover)) + " " + to_string(x.osm); };
    diff_kind("land_cover", keyed(a.land_cover, cover_key), keyed(b.land_cover, cover_key),
              [tol](const LandCover& x, const LandCover& y) -> std::string {
                  double d = max_point_distance(x.outer, y.outer);
                  if (d > tol) return "outline moved " + metres(d);
                  if (x.holes.size() != y.holes.size()) return "number of holes differs";
                  for (size_t i = 0; i < x.holes.size(); ++i)
                      if ((d = max_point_distance(x.holes[i], y.holes[i])) > tol) return "hole moved " + metres(d);
                  return "";
              },
              out);

    auto tree_key = [](const Tree& x) { return std::string(to_string(x.source)) + " " + to_string(x.osm); };
    diff_kind("tree", keyed(a.trees, tree_key), keyed(b.trees, tree_key),
              [tol](const Tree& x, const Tree& y) -> std::string {
                  const double d = length(x.position - y.position);
                  if (d > tol) return "moved " + metres(d);
                  if (std::fabs(x.height - y.height) > tol || std::fabs(x.crown_diameter - y.crown_diameter) > tol)
                      return "size changed";
                  return "";
              },
              out);
    return out;
}

}  // namespace citygen
