#include "render/scene/merge_scenes.h"

#include <algorithm>
#include <cstdio>
#include <iterator>
#include <unordered_map>

#include "common/error.h"
#include "common/scene_io.h"

namespace citygen {

namespace {

std::string origin_text(const SceneHeader& h) {
    char text[64];
    std::snprintf(text, sizeof text, "%.9g,%.9g", h.origin_lat, h.origin_lon);
    return text;
}

bool same_terrain(const HeightField& a, const HeightField& b) {
    return a.origin.x == b.origin.x && a.origin.y == b.origin.y && a.cell == b.cell && a.nx == b.nx && a.ny == b.ny &&
           a.heights == b.heights && a.reference_altitude == b.reference_altitude && a.vertical_datum == b.vertical_datum;
}

// Scene `i` against the first: one frame, one seed, one terrain.
void check_mergeable(const Scene& first, const Scene& s, const std::string& first_name, const std::string& name) {
    const SceneHeader &a = first.header, &b = s.header;
    if (a.origin_lat != b.origin_lat || a.origin_lon != b.origin_lon || a.projection != b.projection)
        throw Error(name + ": origin " + origin_text(b) + " (" + b.projection + ") is not " + first_name + "'s " +
                    origin_text(a) + " (" + a.projection + "); parse the tiles with one --origin");
    if (a.seed != b.seed)
        throw Error(name + ": seed " + std::to_string(b.seed) + " is not " + first_name + "'s " +
                    std::to_string(a.seed) + "; parse the tiles with one --seed");
    if (!same_terrain(first.terrain, s.terrain))
        throw Error(name + ": its terrain is not " + first_name +
                    "'s; scenes with different terrain (--dem) cannot be merged yet");
}

template <typename T>
void append(std::vector<T>& to, std::vector<T>& from) {
    to.insert(to.end(), std::make_move_iterator(from.begin()), std::make_move_iterator(from.end()));
}

int shifted(int index, size_t offset) { return index < 0 ? index : index + static_cast<int>(offset); }

void shift_edges(std::vector<Joint>& joints, size_t offset) {
    for (Joint& j : joints)
        for (uint32_t& e : j.edges) e += static_cast<uint32_t>(offset);
}

// Moves `s`'s lists behind `into`'s, with their indices.
void append_scene(Scene& into, Scene& s) {
    const size_t roads = into.roads.size(), joints = into.joints.size();
    const size_t paths = into.paths.size(), path_joints = into.path_joints.size();
    for (RoadEdge& r : s.roads) r.from_joint = shifted(r.from_joint, joints), r.to_joint = shifted(r.to_joint, joints);
    shift_edges(s.joints, roads);
    for (Sidewalk& w : s.sidewalks) w.road = shifted(w.road, roads), w.joint = shifted(w.joint, joints);
    for (PathEdge& p : s.paths)
        p.from_joint = shifted(p.from_joint, path_joints), p.to_joint = shifted(p.to_joint, path_joints);
    shift_edges(s.path_joints, paths);
    for (Crossing& c : s.crossings) c.road = shifted(c.road, roads);
    append(into.buildings, s.buildings);
    append(into.roads, s.roads);
    append(into.joints, s.joints);
    append(into.sidewalks, s.sidewalks);
    append(into.lamps, s.lamps);
    append(into.land_cover, s.land_cover);
    append(into.trees, s.trees);
    append(into.paths, s.paths);
    append(into.path_joints, s.path_joints);
    append(into.crossings, s.crossings);
    append(into.retaining_walls, s.retaining_walls);
}

// An edge end without a joint, at a node that has one: a tile kept the edge and its neighbour
// the joint. One parse of the whole region joins every edge end at a joint's node to it.
template <typename Edge>
void link_cut_ends(std::vector<Edge>& edges, std::vector<Joint>& joints) {
    std::unordered_map<int64_t, int> joint_at;
    for (size_t j = 0; j < joints.size(); ++j) joint_at.emplace(joints[j].osm.id, static_cast<int>(j));
    auto link = [&](int& end, int64_t node, size_t edge) {
        if (end >= 0) return;
        const auto it = joint_at.find(node);
        if (it == joint_at.end()) return;
        end = it->second;
        joints[it->second].edges.push_back(static_cast<uint32_t>(edge));
    };
    for (size_t e = 0; e < edges.size(); ++e) {
        link(edges[e].from_joint, edges[e].from_node, e);
        link(edges[e].to_joint, edges[e].to_node, e);
    }
}

void cover_bounds(Scene& into, const Scene& s) {
    SceneHeader& h = into.header;
    h.bounds_min = {std::min(h.bounds_min.x, s.header.bounds_min.x), std::min(h.bounds_min.y, s.header.bounds_min.y)};
    h.bounds_max = {std::max(h.bounds_max.x, s.header.bounds_max.x), std::max(h.bounds_max.y, s.header.bounds_max.y)};
    into.ground.min = {std::min(into.ground.min.x, s.ground.min.x), std::min(into.ground.min.y, s.ground.min.y)};
    into.ground.max = {std::max(into.ground.max.x, s.ground.max.x), std::max(into.ground.max.y, s.ground.max.y)};
    h.source += " + " + s.header.source;
}

}  // namespace

Scene merge_scenes(std::vector<Scene> scenes, const std::vector<std::string>& names) {
    if (scenes.empty()) throw Error("no scene to merge");
    auto name = [&](size_t i) { return i < names.size() ? names[i] : "scene " + std::to_string(i + 1); };
    for (size_t i = 1; i < scenes.size(); ++i) check_mergeable(scenes[0], scenes[i], name(0), name(i));
    Scene merged = std::move(scenes[0]);
    for (size_t i = 1; i < scenes.size(); ++i) {
        cover_bounds(merged, scenes[i]);
        append_scene(merged, scenes[i]);
        scenes[i] = Scene();  // freed as it goes: a region's tiles need not be held twice
    }
    if (scenes.size() > 1) {
        link_cut_ends(merged.roads, merged.joints);
        link_cut_ends(merged.paths, merged.path_joints);
    }
    return merged;
}

Scene load_scenes(const std::vector<std::string>& paths) {
    if (paths.size() == 1) return load_scene(paths[0]);
    std::vector<Scene> scenes;
    scenes.reserve(paths.size());
    for (const std::string& path : paths) scenes.push_back(load_scene(path));
    return merge_scenes(std::move(scenes), paths);
}

}  // namespace citygen
