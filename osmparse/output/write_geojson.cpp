#include "osmparse/output/write_geojson.h"

#include <cstdio>
#include <optional>

#include "common/bridge_deck.h"
#include "common/ground.h"
#include "common/retaining_wall.h"
#include "common/scene_io.h"
#include "common/projection.h"
#include "common/stairs.h"

namespace citygen {

namespace {

// With a height field every coordinate carries z, metres above the field's vertical datum:
// a vertex on the ground at the ground height under it (common/ground.h, the surface render
// draws), or a given height (a building's base). Without a field coordinates stay 2D.
class GeoJsonWriter {
public:
    GeoJsonWriter(const Projection& p, const Scene& scene) : projection_(p), scene_(scene) {
        text_ = "{\"type\":\"FeatureCollection\",\"features\":[\n";
    }

    // Each vertex at the ground under it, or on the deck when one is given.
    void polygon(const std::vector<const Ring*>& rings, const std::string& properties, const DeckSurface* deck = nullptr) {
        polygon_at(rings, properties, [deck](Vec2 p) { return deck ? std::optional(deck->height(p)) : std::nullopt; });
    }
    // Every vertex at `height` (relative to the field's reference altitude, like the field).
    void polygon_at_height(const std::vector<const Ring*>& rings, const std::string& properties, double height) {
        polygon_at(rings, properties, [height](Vec2) { return std::optional(height); });
    }
    // Each vertex at the stair's height there (StairPlan::line_height), not the ground's: render
    // draws the strip as the stair's treads, not draped.
    void polygon_on_stair(const Ring& ring, const std::string& properties, const StairPlan& stair) {
        polygon_at({&ring}, properties, [&stair](Vec2 p) { return std::optional(stair.line_height(p)); });
    }
    // At the ground under it.
    void point_feature(Vec2 p, const std::string& properties) { point_feature_at(p, std::nullopt, properties); }
    // At `height`, or the ground under it.
    void point_feature_at(Vec2 p, std::optional<double> height, const std::string& properties) {
        begin("Point");
        text_ += coordinates(p, height);
        end(properties);
    }
    // A line, each point at its height (relative to the field's reference altitude).
    void line_at(const std::vector<Vec3>& points, const std::string& properties) {
        begin("LineString");
        for (size_t i = 0; i < points.size(); ++i)
            text_ += std::string(i ? "," : "") + "[" + coordinates({points[i].x, points[i].y}, points[i].z) + "]";
        end(properties);
    }
    std::string finish() { return text_ + "\n]}\n"; }

private:
    // `height_at(p)`: a vertex's height, or nullopt for the ground under it.
    template <typename HeightAt>
    void polygon_at(const std::vector<const Ring*>& rings, const std::string& properties, HeightAt height_at) {
        begin("Polygon");
        for (size_t r = 0; r < rings.size(); ++r) {
            text_ += r ? ",[" : "[";
            const Ring& ring = *rings[r];
            for (size_t i = 0; i <= ring.size(); ++i) {  // GeoJSON rings repeat the first point
                if (i) text_ += ",";
                const Vec2 p = ring[i % ring.size()];
                text_ += "[" + coordinates(p, height_at(p)) + "]";
            }
            text_ += "]";
        }
        end(properties);
    }
    void begin(const char* type) {
        if (count_++) text_ += ",\n";
        text_ += "{\"type\":\"Feature\",\"geometry\":{\"type\":\"";
        text_ += type;
        text_ += "\",\"coordinates\":[";
    }
    void end(const std::string& properties) { text_ += "]},\"properties\":{" + properties + "}}"; }
    // "lon,lat" without a field, "lon,lat,z" with one.
    std::string coordinates(Vec2 p, std::optional<double> height) const {
        double lat, lon;
        projection_.to_wgs84(p, lat, lon);
        char buf[96];
        if (scene_.terrain.empty()) {
            std::snprintf(buf, sizeof buf, "%.8f,%.8f", lon, lat);
        } else {
            const double z = scene_.terrain.reference_altitude + (height ? *height : ground_height(scene_, p.x, p.y));
            std::snprintf(buf, sizeof buf, "%.8f,%.8f,%.3f", lon, lat, z);
        }
        return buf;
    }
    const Projection& projection_;
    const Scene& scene_;
    std::string text_;
    size_t count_ = 0;
};

std::string num(double v) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3f", v);
    return buf;
}
std::string str(const std::string& s) {
    std::string out = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        if (static_cast<unsigned char>(c) >= 0x20) out += c;
    }
    return out + "\"";
}

// Format 1.1 properties: the height rule, the roof and the colours and materials.
std::string building_look_properties(const Building& b) {
    char wall[16], roof[16];
    std::snprintf(wall, sizeof wall, "#%06x", b.wall_colour & 0xffffffu);
    std::snprintf(roof, sizeof roof, "#%06x", b.roof_colour & 0xffffffu);
    return std::string(",\"type\":") + str(b.type) + ",\"height_rule\":" + str(to_string(b.height_rule)) + ",\"roof_shape\":" +
           str(to_string(b.roof_shape)) + ",\"roof_height\":" + num(b.roof_height) +
           ",\"roof_inferred\":" + (b.roof_inferred ? "true" : "false") +
           ",\"wall_colour\":" + (b.wall_colour ? str(wall) : "null") +
           ",\"roof_colour\":" + (b.roof_colour ? str(roof) : "null") +
           ",\"wall_material\":" + str(to_string(b.wall_material)) +
           ",\"roof_material\":" + str(to_string(b.roof_material)) +
           ",\"generated\":" + (b.generated ? "true" : "false");
}

}  // namespace

std::string scene_to_geojson(const Scene& scene) {
    const Projection projection(scene.header.origin_lat, scene.header.origin_lon);
    GeoJsonWriter w(projection, scene);
    static const char* height_sources[] = {"tagged", "levels", "random"};
    for (const Building& b : scene.buildings) {
        std::vector<const Ring*> rings{&b.outer};
        for (const Ring& h : b.holes) rings.push_back(&h);
        const std::string properties =
            "\"kind\":\"building\",\"osm\":" + str(to_string(b.osm)) + ",\"height\":" + num(b.height) +
            ",\"min_height\":" + num(b.min_height) + ",\"levels\":" + std::to_string(b.levels) +
            ",\"height_source\":\"" + height_sources[static_cast<int>(b.height_source)] +
            "\",\"part\":" + (b.is_part ? "true" : "false") + building_look_properties(b);
        w.polygon_at_height(rings, properties, building_base(scene, b));
    }
    // Bridges on a field lie on their decks (common/bridge_deck.h), as render draws them.
    const std::vector<DeckLine> decks = scene.terrain.empty() ? std::vector<DeckLine>{} : bridge_decks(scene);
    for (size_t k = 0; k < scene.roads.size(); ++k) {
        const RoadEdge& r = scene.roads[k];
        const DeckSurface deck = edge_deck(decks, static_cast<uint32_t>(k));
        w.polygon({&r.quad}, "\"kind\":\"road\",\"osm\":" + str(to_string(r.osm)) + ",\"from_node\":" +
                                 std::to_string(r.from_node) + ",\"to_node\":" + std::to_string(r.to_node) +
                                 ",\"width\":" + num(r.width) + ",\"class\":\"" + to_string(r.road_class) +
                                 "\",\"lanes\":" + std::to_string(r.lanes) + ",\"oneway\":" + (r.oneway ? "true" : "false") +
                                 ",\"bridge\":" + (r.bridge ? "true" : "false") +
                                 ",\"lanes_forward\":" + std::to_string(r.lanes_forward) +
                                 ",\"lanes_backward\":" + std::to_string(r.lanes_backward) +
                                 ",\"centre_line\":" + std::to_string(static_cast<int>(r.centre_line)) +
                                 ",\"edge_lines\":" + (r.edge_lines ? "true" : "false") +
                                 ",\"cycle_lanes\":" + std::to_string(r.cycle_lane_left + r.cycle_lane_right),
                  deck.valid() ? &deck : nullptr);
    }
    for (const Joint& j : scene.joints) {
        const DeckSurface deck = joint_deck(scene, decks, j);
        w.polygon({&j.polygon}, "\"kind\":\"joint\",\"osm\":" + str(to_string(j.osm)) + ",\"edges\":" +
                                    std::to_string(j.edges.size()), deck.valid() ? &deck : nullptr);
    }
    for (const Sidewalk& s : scene.sidewalks) {
        const DeckSurface deck = sidewalk_deck(scene, decks, s);
        w.polygon({&s.polygon}, std::string("\"kind\":\"sidewalk\",\"piece\":\"") +
                                    (s.kind == SidewalkKind::Strip ? "strip" : "corner") +
                                    "\",\"height\":" + num(s.curb_height) +
                                    (s.road >= 0 ? ",\"osm\":" + str(to_string(scene.roads[s.road].osm)) : "") +
                                    (s.joint >= 0 ? ",\"joint\":" + str(to_string(scene.joints[s.joint].osm)) : ""),
                  deck.valid() ? &deck : nullptr);
    }
    const StandingSurface surface(scene);
    for (const Lamp& l : scene.lamps)
        w.point_feature_at({l.position.x, l.position.y}, surface.height({l.position.x, l.position.y}),
                        "\"kind\":\"lamp\",\"osm\":" + str(to_string(l.osm)) + ",\"height\":" + num(l.height) +
                            ",\"source\":\"" + (l.source == LampSource::Tagged ? "tagged" : "generated") + "\"");
    for (const LandCover& c : scene.land_cover) {
        std::vector<const Ring*> rings{&c.outer};
        for (const Ring& h : c.holes) rings.push_back(&h);
        w.polygon(rings, "\"kind\":\"land_cover\",\"class\":\"" + std::string(to_string(c.cover)) +
                             "\",\"osm\":" + str(to_string(c.osm)));
    }
    const std::vector<DeckLine> path_decks = scene.terrain.empty() ? std::vector<DeckLine>{} : path_bridge_decks(scene);
    for (size_t k = 0; k < scene.paths.size(); ++k) {
        const PathEdge& p = scene.paths[k];
        const DeckSurface deck = edge_deck(path_decks, static_cast<uint32_t>(k));
        const std::string properties = "\"kind\":\"path\",\"class\":\"" + std::string(to_string(p.path_class)) +
                                       "\",\"osm\":" + str(to_string(p.osm)) + ",\"width\":" + num(p.width) +
                                       ",\"sidewalk\":" + (p.sidewalk ? "true" : "false") +
                                       (p.bridge ? ",\"bridge\":true" : "");  // only with a field: the same bytes without
        StairPlan stair;
        if (plan_stair(scene, p, &stair))
            w.polygon_on_stair(p.quad, properties, stair);
        else
            w.polygon({&p.quad}, properties, deck.valid() ? &deck : nullptr);
    }
    for (const Joint& j : scene.path_joints) {
        const DeckSurface deck = path_joint_deck(scene, path_decks, j);
        w.polygon({&j.polygon}, "\"kind\":\"path_joint\",\"osm\":" + str(to_string(j.osm)), deck.valid() ? &deck : nullptr);
    }
    for (const Crossing& c : scene.crossings)
        w.point_feature(c.position, std::string("\"kind\":\"") +
                                        (c.kind == CrossingKind::Zebra ? "zebra_crossing" : "stop_line") +
                                        "\",\"osm\":" + str(to_string(c.osm)) + ",\"road\":" +
                                        str(to_string(scene.roads[c.road].osm)));
    for (const Tree& t : scene.trees)
        w.point_feature(t.position, "\"kind\":\"tree\",\"osm\":" + str(to_string(t.osm)) + ",\"height\":" +
                                        num(t.height) + ",\"crown_diameter\":" + num(t.crown_diameter) +
                                        ",\"leaf_type\":\"" +
                                        (t.leaf_type == LeafType::Needleleaved ? "needleleaved" : "broadleaved") +
                                        "\",\"source\":\"" + to_string(t.source) + "\"");
    // Retaining walls (only with a field): the line along the wall's top, as render draws it, a
    // point at each of its stations (common/retaining_wall.h).
    for (const RetainingWall& rw : scene.retaining_walls) {
        std::vector<Vec3> top;
        for (const WallStation& st : wall_stations(scene, rw)) {
            const Vec2 c = (st.left + st.right) * 0.5;
            top.push_back({c.x, c.y, st.top});
        }
        if (top.size() < 2) continue;
        w.line_at(top, "\"kind\":\"retaining_wall\",\"osm\":" + str(to_string(rw.osm)) + ",\"height\":" + num(rw.height) +
                           ",\"height_tagged\":" + (rw.height_tagged ? "true" : "false") + ",\"material\":" +
                           str(to_string(rw.material)));
    }
    return w.finish();
}

void write_geojson(const Scene& scene, const std::string& path) {
    const std::string text = scene_to_geojson(scene);
    write_file_atomically(path, text.data(), text.size());
}

}  // namespace citygen
