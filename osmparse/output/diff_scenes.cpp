#include "osmparse/output/diff_scenes.h"

#include <algorithm>
#include <cmath>
#include <map>

namespace citygen {

namespace {

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

std::string building_key(const Building& x) { return to_string(x.osm) + (x.is_part ? "/part" : ""); }

std::string road_key(const RoadEdge& x) {
    return to_string(x.osm) + ":" + std::to_string(x.from_node) + "-" + std::to_string(x.to_node);
}

std::string joint_key(const Joint& x) { return to_string(x.osm); }

std::string lamp_key(const Lamp& x) {
    return std::string(x.source == LampSource::Tagged ? "tagged " : "generated ") + to_string(x.osm);
}

std::string path_key(const PathEdge& x) {
    return to_string(x.osm) + ":" + std::to_string(x.from_node) + "-" + std::to_string(x.to_node);
}

std::string wall_key(const RetainingWall& x) { return to_string(x.osm); }

std::string crossing_key(const Crossing& x) {
    return std::string(x.kind == CrossingKind::Zebra ? "zebra " : "stop line ") + to_string(x.osm);
}

std::string cover_key(const LandCover& x) { return std::string(to_string(x.cover)) + " " + to_string(x.osm); }

std::string tree_key(const Tree& x) { return std::string(to_string(x.source)) + " " + to_string(x.osm); }

// Sidewalks are keyed by the OSM identity of the road or joint they belong to.
std::string sidewalk_key(const Scene& s, const Sidewalk& x) {
    if (x.kind == SidewalkKind::Strip && x.road >= 0) {
        const RoadEdge& r = s.roads[x.road];
        return "strip " + to_string(r.osm) + ":" + std::to_string(r.from_node) + "-" + std::to_string(r.to_node);
    }
    if (x.kind == SidewalkKind::Corner && x.joint >= 0) return "corner " + to_string(s.joints[x.joint].osm);
    return std::string(x.kind == SidewalkKind::Strip ? "strip" : "corner");
}

std::string building_change(const Building& x, const Building& y, double tol) {
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
}

std::string road_change(const RoadEdge& x, const RoadEdge& y, double tol) {
    double d = max_point_distance(x.quad, y.quad);
    if (d > tol) return "quadrangle moved " + metres(d);
    if ((d = max_point_distance(x.centreline, y.centreline)) > tol) return "centreline moved " + metres(d);
    if (std::fabs(x.width - y.width) > tol) return "width changed by " + metres(std::fabs(x.width - y.width));
    if (x.sidewalk_left != y.sidewalk_left || x.sidewalk_right != y.sidewalk_right) return "sidewalks differ";
    if (x.bridge != y.bridge) return "bridge differs";
    if (x.lanes_forward != y.lanes_forward || x.lanes_backward != y.lanes_backward ||
        x.centre_line != y.centre_line || x.edge_lines != y.edge_lines ||
        x.cycle_lane_left != y.cycle_lane_left || x.cycle_lane_right != y.cycle_lane_right)
        return "lanes or markings differ";
    return "";
}

std::string joint_change(const Joint& x, const Joint& y, double tol) {
    double d = max_point_distance(x.polygon, y.polygon);
    return d > tol ? "polygon moved " + metres(d) : "";
}

std::string sidewalk_change(const Sidewalk& x, const Sidewalk& y, double tol) {
    double d = max_point_distance(x.polygon, y.polygon);
    return d > tol ? "polygon moved " + metres(d) : "";
}

std::string lamp_change(const Lamp& x, const Lamp& y, double tol) {
    double d = length(x.position - y.position);
    return d > tol ? "moved " + metres(d) : "";
}

std::string path_change(const PathEdge& x, const PathEdge& y, double tol) {
    double d = max_point_distance(x.quad, y.quad);
    if (d > tol) return "quadrangle moved " + metres(d);
    if (x.path_class != y.path_class) return "class differs";
    if (x.bridge != y.bridge) return "bridge differs";
    return "";
}

std::string crossing_change(const Crossing& x, const Crossing& y, double tol) {
    const double d = length(x.position - y.position);
    return d > tol ? "moved " + metres(d) : "";
}

std::string land_cover_change(const LandCover& x, const LandCover& y, double tol) {
    double d = max_point_distance(x.outer, y.outer);
    if (d > tol) return "outline moved " + metres(d);
    if (x.holes.size() != y.holes.size()) return "number of holes differs";
    for (size_t i = 0; i < x.holes.size(); ++i)
        if ((d = max_point_distance(x.holes[i], y.holes[i])) > tol) return "hole moved " + metres(d);
    return "";
}

std::string tree_change(const Tree& x, const Tree& y, double tol) {
    const double d = length(x.position - y.position);
    if (d > tol) return "moved " + metres(d);
    if (std::fabs(x.height - y.height) > tol || std::fabs(x.crown_diameter - y.crown_diameter) > tol)
        return "size changed";
    return "";
}

std::string wall_change(const RetainingWall& x, const RetainingWall& y, double tol) {
    const double d = max_point_distance(x.line, y.line);
    if (d > tol) return "line moved " + metres(d);
    if (std::fabs(x.height - y.height) > tol) return "height changed by " + metres(std::fabs(x.height - y.height));
    if (x.material != y.material) return std::string("material ") + to_string(x.material) + " -> " + to_string(y.material);
    return "";
}

// The height fields: the same grid, and every node's altitude within the tolerance.
void diff_terrain(const HeightField& x, const HeightField& y, double tol, std::vector<SceneChange>& out) {
    if (x.empty() != y.empty()) {
        out.push_back({x.empty() ? "added" : "removed", "terrain", ""});
        return;
    }
    if (x.empty()) return;
    if (x.nx != y.nx || x.ny != y.ny || x.cell != y.cell || length(x.origin - y.origin) > tol) {
        out.push_back({"changed", "terrain", "another grid"});
        return;
    }
    double d = 0;
    for (size_t k = 0; k < x.heights.size(); ++k)
        d = std::max(d, std::fabs((x.reference_altitude + x.heights[k]) - (y.reference_altitude + y.heights[k])));
    if (d > tol) out.push_back({"changed", "terrain", "heights differ by up to " + metres(d)});
}

}  // namespace

std::vector<SceneChange> diff_scenes(const Scene& a, const Scene& b, double tol) {
    std::vector<SceneChange> out;
    if (a.header.format_major != b.header.format_major || a.header.format_minor != b.header.format_minor)
        out.push_back({"changed", "header", "format version differs"});
    if (a.header.options != b.header.options) out.push_back({"changed", "header", "parse options differ"});
    auto diff = [&](const char* kind, const auto& items_a, const auto& items_b, auto key, auto change) {
        diff_kind(kind, keyed(items_a, key), keyed(items_b, key),
                  [&](const auto& x, const auto& y) { return change(x, y, tol); }, out);
    };
    diff("building", a.buildings, b.buildings, building_key, building_change);
    diff("road", a.roads, b.roads, road_key, road_change);
    diff("joint", a.joints, b.joints, joint_key, joint_change);
    diff_kind("sidewalk", keyed(a.sidewalks, [&](const Sidewalk& x) { return sidewalk_key(a, x); }),
              keyed(b.sidewalks, [&](const Sidewalk& x) { return sidewalk_key(b, x); }),
              [tol](const Sidewalk& x, const Sidewalk& y) { return sidewalk_change(x, y, tol); }, out);
    diff("lamp", a.lamps, b.lamps, lamp_key, lamp_change);
    diff("path", a.paths, b.paths, path_key, path_change);
    diff("path_joint", a.path_joints, b.path_joints, joint_key, joint_change);
    diff("crossing", a.crossings, b.crossings, crossing_key, crossing_change);
    diff("land_cover", a.land_cover, b.land_cover, cover_key, land_cover_change);
    diff("tree", a.trees, b.trees, tree_key, tree_change);
    diff_terrain(a.terrain, b.terrain, tol, out);
    diff("retaining_wall", a.retaining_walls, b.retaining_walls, wall_key, wall_change);
    return out;
}

}  // namespace citygen
