#include "render/scene/merge_scenes.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <iterator>
#include <limits>
#include <unordered_map>

#include "common/error.h"
#include "common/scene_io.h"
#include "common/scene_limits.h"

namespace citygen {

namespace {

std::string origin_text(const SceneHeader& h) {
    char text[64];
    std::snprintf(text, sizeof text, "%.9g,%.9g", h.origin_lat, h.origin_lon);
    return text;
}

// Scene `i` against the first: one frame, one seed, terrain on one grid or none.
void check_mergeable(const Scene& first, const Scene& s, const std::string& first_name, const std::string& name) {
    const SceneHeader &a = first.header, &b = s.header;
    if (a.origin_lat != b.origin_lat || a.origin_lon != b.origin_lon || a.projection != b.projection)
        throw Error(name + ": origin " + origin_text(b) + " (" + b.projection + ") is not " + first_name + "'s " +
                    origin_text(a) + " (" + a.projection + "); parse the tiles with one --origin");
    if (a.seed != b.seed)
        throw Error(name + ": seed " + std::to_string(b.seed) + " is not " + first_name + "'s " +
                    std::to_string(a.seed) + "; parse the tiles with one --seed");
    const HeightField &f = first.terrain, &g = s.terrain;
    if (f.empty() != g.empty())
        throw Error((g.empty() ? name : first_name) + " has no terrain and " + (g.empty() ? first_name : name) +
                    " has; parse every tile with the same --dem");
    if (f.empty()) return;
    if (f.cell != g.cell)
        throw Error(name + ": terrain nodes every " + std::to_string(g.cell) + " m, not " + first_name + "'s " +
                    std::to_string(f.cell) + " m; parse the tiles with one --dem-resolution");
    if (f.vertical_datum != g.vertical_datum)
        throw Error(name + ": terrain heights above " + g.vertical_datum + ", not " + first_name + "'s " +
                    f.vertical_datum);
}

// The node index of a field's origin on the lattice every tile's nodes lie on (multiples of the
// cell in the shared frame, osmparse's grid_over).
int64_t lattice_index(double coordinate, double cell, const std::string& name) {
    const double index = coordinate / cell;
    const double nearest = std::round(index);
    if (!(std::fabs(index - nearest) < 1e-6) || !(std::fabs(nearest) < 1e12))
        throw Error(name + ": its terrain's nodes are not on multiples of the cell; parse it again with this osmparse");
    return static_cast<int64_t>(nearest);
}

// The tiles' fields as one: it covers them all, heights above the lowest of their reference
// altitudes. Each node is taken from the tile it lies deepest inside (farthest from that tile's
// grid edge, the first tile on a tie): the tile whose core holds it, which saw every way within
// its overlap that the terrain is fitted to. A node no tile covers (a gap in an irregular set of
// tiles) takes the value of the nearest tile's edge, as a field does beyond its edge.
HeightField merge_terrains(std::vector<HeightField> fields, const std::vector<std::string>& names) {
    if (fields.size() == 1 || fields.front().empty()) return std::move(fields.front());
    struct Extent {
        int64_t i0, j0, i1, j1;  // lattice indices of the first and last nodes
        // Nodes from the edge, negative outside; used within the merged grid, whose sides are
        // within the node limit.
        int32_t depth(int64_t i, int64_t j) const {
            return static_cast<int32_t>(std::min({i - i0, i1 - i, j - j0, j1 - j}));
        }
    };
    const double cell = fields.front().cell;
    std::vector<Extent> extents;
    double reference = fields.front().reference_altitude;
    for (size_t t = 0; t < fields.size(); ++t) {
        const HeightField& f = fields[t];
        const int64_t i0 = lattice_index(f.origin.x, cell, names[t]), j0 = lattice_index(f.origin.y, cell, names[t]);
        extents.push_back({i0, j0, i0 + f.nx - 1, j0 + f.ny - 1});
        reference = std::min(reference, f.reference_altitude);
    }
    Extent all = extents.front();
    for (const Extent& e : extents)
        all = {std::min(all.i0, e.i0), std::min(all.j0, e.j0), std::max(all.i1, e.i1), std::max(all.j1, e.j1)};
    HeightField merged;
    merged.origin = {all.i0 * cell, all.j0 * cell};
    merged.cell = cell;
    merged.reference_altitude = reference;
    merged.vertical_datum = fields.front().vertical_datum;
    const uint64_t nx = static_cast<uint64_t>(all.i1 - all.i0 + 1), ny = static_cast<uint64_t>(all.j1 - all.j0 + 1);
    if (!height_field_within_limit(merged.origin, cell, nx, ny))
        throw Error("the tiles' terrain together is " + std::to_string(nx) + " x " + std::to_string(ny) +
                    " nodes, beyond the limit of " + std::to_string(kMaxHeightFieldNodes) +
                    "; parse them with a coarser --dem-resolution");
    merged.nx = static_cast<uint32_t>(nx), merged.ny = static_cast<uint32_t>(ny);
    merged.heights.assign(nx * ny, 0.0f);
    constexpr int32_t kUncovered = std::numeric_limits<int32_t>::min();
    std::vector<int32_t> best(nx * ny, kUncovered);  // the depth of the tile each node was taken from
    auto height_in = [&](size_t t, int64_t i, int64_t j) {  // tile t's node nearest (i, j), above `reference`
        const Extent& e = extents[t];
        const uint64_t k = static_cast<uint64_t>(std::clamp(j, e.j0, e.j1) - e.j0) * fields[t].nx +
                           static_cast<uint64_t>(std::clamp(i, e.i0, e.i1) - e.i0);
        return static_cast<float>(fields[t].heights[k] + (fields[t].reference_altitude - reference));
    };
    for (size_t t = 0; t < fields.size(); ++t) {
        const Extent& e = extents[t];
        for (int64_t j = e.j0; j <= e.j1; ++j) {
            for (int64_t i = e.i0; i <= e.i1; ++i) {
                const uint64_t k = static_cast<uint64_t>(j - all.j0) * nx + static_cast<uint64_t>(i - all.i0);
                if (e.depth(i, j) <= best[k]) continue;
                best[k] = e.depth(i, j);
                merged.heights[k] = height_in(t, i, j);
            }
        }
    }
    for (int64_t j = all.j0; j <= all.j1; ++j) {
        for (int64_t i = all.i0; i <= all.i1; ++i) {
            const uint64_t k = static_cast<uint64_t>(j - all.j0) * nx + static_cast<uint64_t>(i - all.i0);
            if (best[k] != kUncovered) continue;
            size_t nearest = 0;
            for (size_t t = 1; t < fields.size(); ++t)
                if (extents[t].depth(i, j) > extents[nearest].depth(i, j)) nearest = t;
            merged.heights[k] = height_in(nearest, i, j);
        }
    }
    return merged;
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
    std::vector<HeightField> fields;
    std::vector<std::string> field_names;
    for (size_t i = 0; i < scenes.size(); ++i) {
        fields.push_back(std::move(scenes[i].terrain));
        field_names.push_back(name(i));
    }
    Scene merged = std::move(scenes[0]);
    merged.terrain = merge_terrains(std::move(fields), field_names);
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
