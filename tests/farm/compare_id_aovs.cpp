// compare_id_aovs: how many pixels of two renders of the same view show the same object, by the
// id AOVs (render --aovs id) of each and the scenes they were rendered from. An id is an index
// into its scene's list, and a merged set of tiles lists the objects in another order than one
// scene of the whole region: each pixel's object is compared by what it is in the map (its OSM
// object, the nodes of an edge, a point or centroid to the centimetre).
//
//   build/bin/compare_id_aovs [--why] A.exr A.scene -- B.exr B1.scene [B2.scene ...]
// --why: also the ten commonest pairs of objects that differ, with their pixel counts.
// Prints "ids_equal_percent: P" (of every pixel) and "object_ids_equal_percent: P" (of the
// pixels where either shows an object); exit 0, or 1 with one line on a bad input.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include <OpenImageIO/imagebuf.h>

#include "common/error.h"
#include "render/scene/geometry_mode.h"
#include "render/scene/merge_scenes.h"

using namespace citygen;

namespace {

std::string at_cm(Vec2 p) {
    char text[64];
    std::snprintf(text, sizeof text, "@%.0f,%.0f", std::round(p.x * 100), std::round(p.y * 100));
    return text;
}

Vec2 middle(const Ring& ring) {
    Vec2 sum{0, 0};
    for (Vec2 p : ring) sum = sum + p;
    return ring.empty() ? sum : sum * (1.0 / static_cast<double>(ring.size()));
}

template <typename Edge>
std::string edge_name(const Edge& e) {
    return to_string(e.osm) + ":" + std::to_string(e.from_node) + "-" + std::to_string(e.to_node);
}

// What object (kind, index) of `scene` is in the map; "" for the sky.
std::string identity(const Scene& s, int kind, size_t i) {
    auto check = [&](size_t size) {
        if (i >= size)
            throw Error("an id AOV names object " + std::to_string(i) + " of kind " + std::to_string(kind) +
                        " beyond its scene");
    };
    switch (static_cast<ObjectKind>(kind)) {
        case ObjectKind::None: return "";
        case ObjectKind::Building:
            check(s.buildings.size());
            return "b" + to_string(s.buildings[i].osm) + at_cm(middle(s.buildings[i].outer));
        case ObjectKind::Road: check(s.roads.size()); return "r" + edge_name(s.roads[i]);
        case ObjectKind::Joint: check(s.joints.size()); return "j" + to_string(s.joints[i].osm);
        case ObjectKind::Sidewalk: check(s.sidewalks.size()); return "s" + at_cm(middle(s.sidewalks[i].polygon));
        case ObjectKind::Terrain: return "terrain";
        case ObjectKind::Lamp:
            check(s.lamps.size());
            return "l" + to_string(s.lamps[i].osm) + at_cm({s.lamps[i].position.x, s.lamps[i].position.y});
        case ObjectKind::LandCover:
            check(s.land_cover.size());
            // The sea is no OSM object but what the coastline closes within an extract's box:
            // a tile's pieces are other polygons than one parse's, the same water.
            if (s.land_cover[i].cover == LandCoverClass::Sea) return "sea";
            return "c" + to_string(s.land_cover[i].osm) + at_cm(middle(s.land_cover[i].outer));
        case ObjectKind::Tree:
            check(s.trees.size());
            return "t" + to_string(s.trees[i].osm) + at_cm(s.trees[i].position);
        case ObjectKind::Path: check(s.paths.size()); return "p" + edge_name(s.paths[i]);
        case ObjectKind::PathJoint: check(s.path_joints.size()); return "q" + to_string(s.path_joints[i].osm);
        case ObjectKind::RetainingWall:
            check(s.retaining_walls.size());
            return "w" + to_string(s.retaining_walls[i].osm) + at_cm(middle(s.retaining_walls[i].line));
    }
    throw Error("an id AOV has the unknown kind " + std::to_string(kind));
}

// Per pixel, the identity of its object.
std::vector<std::string> pixel_objects(const std::string& exr, const std::vector<std::string>& scenes, int& width,
                                       int& height) {
    OIIO::ImageBuf image(exr);
    if (!image.read(0, 0, true, OIIO::TypeDesc::FLOAT)) throw Error(exr + ": cannot read: " + image.geterror());
    const OIIO::ImageSpec& spec = image.spec();
    const int kind = spec.channelindex("id.kind"), index = spec.channelindex("id.index");
    if (kind < 0 || index < 0) throw Error(exr + ": no id AOV (render it with --aovs id)");
    const Scene scene = load_scenes(scenes);
    width = spec.width;
    height = spec.height;
    std::vector<std::string> out;
    out.reserve(static_cast<size_t>(width) * height);
    std::vector<float> pixel(spec.nchannels);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            image.getpixel(x, y, pixel.data(), spec.nchannels);
            out.push_back(identity(scene, static_cast<int>(pixel[kind]), static_cast<size_t>(pixel[index])));
        }
    return out;
}

void print_commonest(const std::map<std::pair<std::string, std::string>, size_t>& differences) {
    std::vector<std::pair<size_t, std::pair<std::string, std::string>>> sorted;
    for (const auto& [pair, n] : differences) sorted.push_back({n, pair});
    std::sort(sorted.rbegin(), sorted.rend());
    for (size_t i = 0; i < std::min<size_t>(10, sorted.size()); ++i)
        std::printf("differs: %zu pixels: %s vs %s\n", sorted[i].first,
                    sorted[i].second.first.empty() ? "sky" : sorted[i].second.first.c_str(),
                    sorted[i].second.second.empty() ? "sky" : sorted[i].second.second.c_str());
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> a, b;
    bool second = false, why = false;
    for (int i = 1; i < argc; ++i) {
        if (std::string(argv[i]) == "--why")
            why = true;
        else if (std::string(argv[i]) == "--")
            second = true;
        else
            (second ? b : a).push_back(argv[i]);
    }
    if (a.size() < 2 || b.size() < 2) {
        std::fprintf(stderr, "usage: %s A.exr A.scene... -- B.exr B.scene...\n", argv[0]);
        return 2;
    }
    try {
        int wa = 0, ha = 0, wb = 0, hb = 0;
        const std::vector<std::string> pa = pixel_objects(a[0], {a.begin() + 1, a.end()}, wa, ha);
        const std::vector<std::string> pb = pixel_objects(b[0], {b.begin() + 1, b.end()}, wb, hb);
        if (wa != wb || ha != hb) throw Error("the two images differ in size");
        size_t equal = 0, objects = 0, equal_objects = 0;
        std::map<std::pair<std::string, std::string>, size_t> differences;
        for (size_t i = 0; i < pa.size(); ++i) {
            const bool same = pa[i] == pb[i];
            if (!same) ++differences[{pa[i], pb[i]}];
            equal += same;
            if (pa[i].empty() && pb[i].empty()) continue;
            ++objects;
            equal_objects += same;
        }
        std::printf("pixels: %zu\nobject_pixels: %zu\nids_equal_percent: %.3f\nobject_ids_equal_percent: %.3f\n",
                    pa.size(), objects, 100.0 * equal / pa.size(), objects ? 100.0 * equal_objects / objects : 100.0);
        if (why) print_commonest(differences);
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "compare_id_aovs: %s\n", e.what());
        return 1;
    }
}
