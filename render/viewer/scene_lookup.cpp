#include "render/viewer/scene_lookup.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include <nlohmann/json.hpp>

#include "common/ground.h"
#include "common/projection.h"
#include "render/scene/geometry_mode.h"

namespace citygen {

namespace {

using nlohmann::json;

const char* osm_type_name(OsmType type) {
    return type == OsmType::Node ? "node" : type == OsmType::Way ? "way" : "relation";
}

std::string metres(double v) {
    char text[32];
    std::snprintf(text, sizeof text, "%.1f m", v);
    return text;
}

json building_fields(const Scene& scene, const Building& b) {
    json f;
    f["height"] = metres(b.height);
    if (b.min_height > 0) f["min_height"] = metres(b.min_height);
    f["height_rule"] = to_string(b.height_rule);
    if (b.levels > 0) f["levels"] = std::to_string(b.levels);
    if (!b.type.empty()) f["type"] = b.type;
    if (b.is_part) f["part"] = "yes";
    f["roof_shape"] = std::string(to_string(b.roof_shape)) + (b.roof_inferred ? " (inferred)" : "");
    if (b.roof_height > 0) f["roof_height"] = metres(b.roof_height);
    f["wall_material"] = to_string(b.wall_material);
    f["roof_material"] = to_string(b.roof_material);
    if (b.wall_colour) {
        char colour[16];
        std::snprintf(colour, sizeof colour, "#%06x", b.wall_colour & 0xffffff);
        f["wall_colour"] = std::string(colour) + (b.colour_inferred & kWallColourInferred ? " (inferred)" : "");
    }
    f["base"] = metres(building_base(scene, b));
    if (b.generated) f["generated"] = "yes (--fill-empty-blocks)";
    return f;
}

json road_fields(const RoadEdge& r) {
    json f;
    f["highway"] = to_string(r.road_class);
    f["width"] = metres(r.width);
    f["lanes"] = std::to_string(r.lanes) + " (" + std::to_string(r.lanes_forward) + " forward, " +
                 std::to_string(r.lanes_backward) + " backward)";
    if (r.oneway) f["oneway"] = "yes";
    if (r.bridge) f["bridge"] = "yes";
    return f;
}

// The OSM reference and fields of the object a hit names; false when the index is not valid.
bool object_info(const Scene& scene, const Hit& at, OsmRef& osm, json& fields) {
    const size_t i = at.object;
    switch (at.kind) {
        case ObjectKind::Building:
            if (i >= scene.buildings.size()) return false;
            osm = scene.buildings[i].osm, fields = building_fields(scene, scene.buildings[i]);
            return true;
        case ObjectKind::Road:
            if (i >= scene.roads.size()) return false;
            osm = scene.roads[i].osm, fields = road_fields(scene.roads[i]);
            return true;
        case ObjectKind::Joint:
            if (i >= scene.joints.size()) return false;
            osm = scene.joints[i].osm, fields["roads"] = std::to_string(scene.joints[i].edges.size());
            return true;
        case ObjectKind::Sidewalk:
            if (i >= scene.sidewalks.size()) return false;
            // A sidewalk is no OSM object of its own: it names its road's way.
            if (const int road = scene.sidewalks[i].road; road >= 0 && static_cast<size_t>(road) < scene.roads.size())
                osm = scene.roads[road].osm;
            fields["curb_height"] = metres(scene.sidewalks[i].curb_height);
            return true;
        case ObjectKind::Lamp:
            if (i >= scene.lamps.size()) return false;
            osm = scene.lamps[i].osm, fields["height"] = metres(scene.lamps[i].height);
            fields["source"] = scene.lamps[i].source == LampSource::Tagged ? "mapped" : "generated";
            return true;
        case ObjectKind::LandCover:
            if (i >= scene.land_cover.size()) return false;
            osm = scene.land_cover[i].osm, fields["cover"] = to_string(scene.land_cover[i].cover);
            return true;
        case ObjectKind::Tree:
            if (i >= scene.trees.size()) return false;
            osm = scene.trees[i].osm, fields["height"] = metres(scene.trees[i].height);
            fields["crown"] = metres(scene.trees[i].crown_diameter);
            fields["source"] = to_string(scene.trees[i].source);
            return true;
        case ObjectKind::Path:
            if (i >= scene.paths.size()) return false;
            osm = scene.paths[i].osm, fields["class"] = to_string(scene.paths[i].path_class);
            fields["width"] = metres(scene.paths[i].width);
            return true;
        case ObjectKind::PathJoint:
            if (i >= scene.path_joints.size()) return false;
            osm = scene.path_joints[i].osm;
            return true;
        case ObjectKind::RetainingWall:
            if (i >= scene.retaining_walls.size()) return false;
            osm = scene.retaining_walls[i].osm, fields["height"] = metres(scene.retaining_walls[i].height);
            fields["material"] = to_string(scene.retaining_walls[i].material);
            return true;
        case ObjectKind::Terrain:
        case ObjectKind::None:
            return false;
    }
    return false;
}

json flat_ring(const Ring& ring) {
    json points = json::array();
    for (Vec2 p : ring) points.push_back(std::round(p.x * 10) / 10), points.push_back(std::round(p.y * 10) / 10);
    return points;
}

// The parts of a query "w123": its type and id.
bool parse_osm_ref(const std::string& text, OsmRef& ref) {
    if (text.size() < 2 || text.size() > 21) return false;
    const char t = static_cast<char>(std::tolower(static_cast<unsigned char>(text[0])));
    if (t != 'n' && t != 'w' && t != 'r') return false;
    char* end = nullptr;
    const long long id = std::strtoll(text.c_str() + 1, &end, 10);
    if (*end != '\0' || id <= 0 || !std::isdigit(static_cast<unsigned char>(text[1]))) return false;
    ref = {t == 'n' ? OsmType::Node : t == 'w' ? OsmType::Way : OsmType::Relation, id};
    return true;
}

// The centre and radius of the points of every object with that reference.
template <class Visit>
void for_each_point_of(const Scene& scene, const OsmRef& ref, Visit visit) {
    for (const Building& b : scene.buildings)
        if (b.osm == ref)
            for (Vec2 p : b.outer) visit(p);
    for (const RoadEdge& r : scene.roads)
        if (r.osm == ref)
            for (Vec2 p : r.centreline) visit(p);
    for (const PathEdge& r : scene.paths)
        if (r.osm == ref)
            for (Vec2 p : r.centreline) visit(p);
    for (const LandCover& c : scene.land_cover)
        if (c.osm == ref)
            for (Vec2 p : c.outer) visit(p);
    for (const Lamp& l : scene.lamps)
        if (l.osm == ref) visit(Vec2{l.position.x, l.position.y});
    for (const Tree& t : scene.trees)
        if (t.osm == ref) visit(t.position);
}

}  // namespace

std::string describe_hit(const Scene& scene, bool hit, const Hit& at) {
    json answer;
    if (!hit) {
        answer["kind"] = "sky";
        return answer.dump(-1, ' ', false, json::error_handler_t::replace);
    }
    answer["kind"] = to_string(at.kind);
    answer["index"] = at.object;
    answer["point"] = {std::round(at.position.x * 10) / 10, std::round(at.position.y * 10) / 10,
                       std::round(at.position.z * 10) / 10};
    OsmRef osm;
    json fields = json::object();
    if (object_info(scene, at, osm, fields) && osm.id != 0) {
        answer["osm"] = to_string(osm);
        answer["osm_type"] = osm_type_name(osm.type);
        answer["osm_id"] = osm.id;
    }
    answer["fields"] = fields;
    return answer.dump(-1, ' ', false, json::error_handler_t::replace);
}

std::string scene_map_json(const Scene& scene) {
    json map;
    map["bounds"] = {{"min", {scene.header.bounds_min.x, scene.header.bounds_min.y}},
                     {"max", {scene.header.bounds_max.x, scene.header.bounds_max.y}}};
    json buildings = json::array(), roads = json::array(), water = json::array();
    for (const Building& b : scene.buildings)
        if (!b.is_part && b.outer.size() >= 3) buildings.push_back(flat_ring(b.outer));
    for (const RoadEdge& r : scene.roads) roads.push_back(flat_ring(r.centreline));
    for (const LandCover& c : scene.land_cover)
        if (c.cover == LandCoverClass::Water || c.cover == LandCoverClass::Sea) water.push_back(flat_ring(c.outer));
    map["buildings"] = std::move(buildings);
    map["roads"] = std::move(roads);
    map["water"] = std::move(water);
    return map.dump(-1, ' ', false, json::error_handler_t::replace);
}

std::optional<Place> find_place(const Scene& scene, const std::string& query, std::string& why) {
    OsmRef ref;
    Vec2 centre;
    double radius = 0;
    if (parse_osm_ref(query, ref)) {
        Vec2 lo{1e30, 1e30}, hi{-1e30, -1e30};
        size_t count = 0;
        for_each_point_of(scene, ref, [&](Vec2 p) {
            lo = {std::min(lo.x, p.x), std::min(lo.y, p.y)}, hi = {std::max(hi.x, p.x), std::max(hi.y, p.y)};
            ++count;
        });
        if (count == 0) {
            why = query + ": no object of this scene has that OSM id";
            return std::nullopt;
        }
        centre = {(lo.x + hi.x) / 2, (lo.y + hi.y) / 2};
        radius = std::max(1.0, 0.5 * std::hypot(hi.x - lo.x, hi.y - lo.y));
    } else {
        double lat = 0, lon = 0;
        char tail = 0;
        if (std::sscanf(query.c_str(), "%lf ,%lf %c", &lat, &lon, &tail) != 2 || !(std::fabs(lat) <= 90) ||
            !(std::fabs(lon) <= 180)) {
            why = "expected lat,lon in degrees (e.g. 43.7384,7.4246) or an OSM id (w123, n5, r7)";
            return std::nullopt;
        }
        if (scene.header.projection != Projection::name()) {
            why = "this scene's projection '" + scene.header.projection + "' is not one render knows";
            return std::nullopt;
        }
        centre = Projection(scene.header.origin_lat, scene.header.origin_lon).to_local(lat, lon);
        if (!(std::hypot(centre.x, centre.y) <= 50000)) {
            why = "that place is more than 50 km from the scene";
            return std::nullopt;
        }
        radius = 50;
    }
    return Place{{centre.x, centre.y, ground_height(scene, centre.x, centre.y)}, radius};
}

}  // namespace citygen
