#include "common/scene_io.h"

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <memory>
#include <iterator>
#include <thread>
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <tbb/parallel_for.h>

#include "common/error.h"
#include "common/output_target.h"
#include "common/scene_limits.h"
#include "scene_generated.h"

namespace citygen {

const char* to_string(LandCoverClass c) {
    static const char* const names[kLandCoverClassCount] = {"water", "sea",  "green",    "forest",
                                                            "paved", "sand", "farmland", "built_up"};
    const int i = static_cast<int>(c);
    return i < kLandCoverClassCount ? names[i] : "?";
}

const char* to_string(TreeSource s) {
    return s == TreeSource::Mapped ? "mapped" : s == TreeSource::Row ? "row" : "scattered";
}

const char* to_string(PathClass c) {
    static const char* const names[kPathClassCount] = {"footway", "path",  "cycleway", "pedestrian",
                                                       "steps",   "track", "bridleway", "rail",
                                                       "tram",    "light_rail", "subway"};
    const int i = static_cast<int>(c);
    return i < kPathClassCount ? names[i] : "?";
}

const char* to_string(RoadClass c) {
    static const char* const names[] = {"motorway",     "trunk",       "primary",       "secondary", "tertiary",
                                        "unclassified", "residential", "living_street", "service",   "other"};
    const auto i = static_cast<size_t>(c);
    return i < sizeof names / sizeof *names ? names[i] : "?";
}

std::string to_string(OsmRef ref) {
    const char prefix = ref.type == OsmType::Node ? 'n' : ref.type == OsmType::Way ? 'w' : 'r';
    return prefix + std::to_string(ref.id);
}

const char* to_string(RoofShape shape) {
    static const char* const names[kRoofShapeCount] = {"flat", "skillion", "gabled", "hipped",
                                                       "half-hipped", "pyramidal", "gambrel", "mansard",
                                                       "dome", "onion", "round"};
    const int i = static_cast<int>(shape);
    return i < kRoofShapeCount ? names[i] : "unknown";
}

const char* to_string(HeightRule rule) {
    static const char* const names[] = {"tagged", "levels", "neighbours", "type and area", "random"};
    const int i = static_cast<int>(rule);
    return i <= static_cast<int>(HeightRule::Random) ? names[i] : "unknown";
}

const char* to_string(WallMaterial material) {
    static const char* const names[kWallMaterialCount] = {"plaster", "brick", "concrete", "stone",
                                                          "glass", "wood", "metal"};
    const int i = static_cast<int>(material);
    return i < kWallMaterialCount ? names[i] : "unknown";
}

const char* to_string(RoofMaterial material) {
    static const char* const names[kRoofMaterialCount] = {"roof_tiles", "slate", "metal", "copper", "concrete",
                                                          "tar_paper", "thatch", "glass", "grass"};
    const int i = static_cast<int>(material);
    return i < kRoofMaterialCount ? names[i] : "unknown";
}

namespace {

namespace fb = citygen::fb;

fb::Vec2 to_fb(Vec2 p) { return {static_cast<float>(p.x), static_cast<float>(p.y)}; }
fb::Vec3 to_fb(Vec3 p) {
    return {static_cast<float>(p.x), static_cast<float>(p.y), static_cast<float>(p.z)};
}
fb::OsmRef to_fb(OsmRef r) { return {static_cast<fb::OsmType>(r.type), r.id}; }

using Builder = flatbuffers::FlatBufferBuilder;

flatbuffers::Offset<flatbuffers::Vector<const fb::Vec2*>> points(Builder& b,
                                                                 const std::vector<Vec2>& pts) {
    thread_local std::vector<fb::Vec2> v;  // reused: a scene has hundreds of thousands of rings
    v.clear();
    for (Vec2 p : pts) v.push_back(to_fb(p));
    return b.CreateVectorOfStructs(v);
}

flatbuffers::Offset<fb::Ring> ring(Builder& b, const Ring& r) {
    return fb::CreateRing(b, points(b, r));
}

// ---- decoding: never trust the bytes -------------------------------------------------

struct Checker {
    const std::string& name;
    [[noreturn]] void fail(const std::string& what) const {
        throw Error(name + ": " + what);
    }
    double finite(float v, const char* what) const {
        if (!std::isfinite(v)) fail(std::string("non-finite coordinate in ") + what);
        return v;
    }
    // A coordinate: finite and within kMaxCoordinate of the origin.
    double coordinate(float v, const char* what, double limit = kMaxCoordinate) const {
        finite(v, what);
        if (!coordinate_within_limit(v, limit))
            fail(std::string("coordinate in ") + what + " is " + std::to_string(v) + " m from the origin (limit " +
                 std::to_string(static_cast<long>(limit)) + " m)");
        return v;
    }
    // A height or curb height in [0, kMaxHeight] metres.
    double height(float v, const char* what) const {
        finite(v, what);
        if (v < 0 || v > kMaxHeight)
            fail(std::string(what) + " " + std::to_string(v) + " m outside [0, " +
                 std::to_string(static_cast<long>(kMaxHeight)) + "] m");
        return v;
    }
    Vec2 vec(const fb::Vec2* p, const char* what) const {
        if (!p) fail(std::string("missing point in ") + what);
        return {coordinate(p->x(), what), coordinate(p->y(), what)};
    }
    std::vector<Vec2> pts(const flatbuffers::Vector<const fb::Vec2*>* v, const char* what,
                          size_t max_points = kMaxRingPoints, double max_extent = kMaxObjectExtent) const {
        std::vector<Vec2> out;
        if (!v) return out;
        if (v->size() > max_points)
            fail(std::string(what) + " has " + std::to_string(v->size()) + " points (limit " +
                 std::to_string(max_points) + ")");
        out.reserve(v->size());
        for (const fb::Vec2* p : *v) out.push_back(vec(p, what));
        extent(out, what, max_extent);
        return out;
    }
    // One object's points fit in a max_extent square.
    void extent(const std::vector<Vec2>& points, const char* what, double max_extent = kMaxObjectExtent) const {
        if (!extent_within_limit(points, max_extent))
            fail(std::string(what) + " is over " + std::to_string(static_cast<long>(max_extent)) + " m across");
    }
    Ring ring(const fb::Ring* r, const char* what, size_t max_points = kMaxRingPoints,
              double max_extent = kMaxObjectExtent) const {
        if (!r) fail(std::string("missing ring in ") + what);
        return pts(r->points(), what, max_points, max_extent);
    }
    // A ring the renderer extrudes and triangulates: at least 3 points, not all on one line.
    void area_ring(const Ring& ring, const char* what) const {
        if (ring.size() < 3) fail(std::string(what) + " has fewer than 3 points");
        if (!(std::fabs(signed_area(ring)) > 0)) fail(std::string(what) + " has zero area (points identical or collinear)");
    }
    OsmRef osm(const fb::OsmRef* r) const {
        if (!r) return {};
        if (r->type() > fb::OsmType::MAX) fail("invalid OSM object type");
        return {static_cast<OsmType>(r->type()), r->id()};
    }
    int index(int i, size_t count, const char* what) const {
        if (i < -1 || i >= static_cast<int64_t>(count))
            fail(std::string(what) + " index " + std::to_string(i) + " out of range");
        return i;
    }
};

std::string str(const flatbuffers::String* s) { return s ? s->str() : std::string(); }

flatbuffers::Offset<flatbuffers::Vector<flatbuffers::Offset<fb::RoofFace>>> encode_roof_faces(
    Builder& b, const std::vector<RoofFace>& faces) {
    std::vector<flatbuffers::Offset<fb::RoofFace>> out;
    thread_local std::vector<fb::Vec3> pts;  // reused, as in points()
    for (const RoofFace& face : faces) {
        pts.clear();
        for (Vec3 p : face.points) pts.push_back(to_fb(p));
        out.push_back(fb::CreateRoofFace(b, b.CreateVectorOfStructs(pts), static_cast<fb::RoofFaceKind>(face.kind)));
    }
    return b.CreateVector(out);
}

// Format 1.1 building fields (absent in 1.0 files, where they read as their defaults).
void decode_building_look(const fb::Building* x, const Checker& check, Building& bld) {
    if (x->roof_shape() > fb::RoofShape::MAX) check.fail("invalid roof shape");
    bld.roof_shape = static_cast<RoofShape>(x->roof_shape());
    bld.roof_height = check.finite(x->roof_height(), "roof height");
    if (bld.roof_height < 0 || bld.roof_height > bld.height - bld.min_height + 1e-3)
        check.fail("roof height outside the building");
    bld.roof_inferred = x->roof_inferred();
    if (x->roof_faces())
        for (const fb::RoofFace* f : *x->roof_faces()) {
            RoofFace face;
            if (f->kind() > fb::RoofFaceKind::MAX) check.fail("invalid roof face kind");
            face.kind = static_cast<RoofFaceKind>(f->kind());
            if (!f->points() || f->points()->size() < 3) check.fail("roof face with fewer than 3 points");
            if (f->points()->size() > kMaxRingPoints) check.fail("roof face with too many points");
            for (const fb::Vec3* p : *f->points())
                face.points.push_back({check.coordinate(p->x(), "roof face"), check.coordinate(p->y(), "roof face"),
                                       check.coordinate(p->z(), "roof face")});
            std::vector<Vec2> footprint;
            for (const Vec3& p : face.points) footprint.push_back({p.x, p.y});
            check.extent(footprint, "roof face");
            bld.roof_faces.push_back(std::move(face));
        }
    if (x->height_rule() > fb::HeightRule::MAX) check.fail("invalid height rule");
    bld.height_rule = static_cast<HeightRule>(x->height_rule());
    bld.wall_colour = x->wall_colour();
    bld.roof_colour = x->roof_colour();
    bld.colour_inferred = x->colour_inferred();
    if (x->wall_material() > fb::WallMaterial::MAX) check.fail("invalid wall material");
    bld.wall_material = static_cast<WallMaterial>(x->wall_material());
    if (x->roof_material() > fb::RoofMaterial::MAX) check.fail("invalid roof material");
    bld.roof_material = static_cast<RoofMaterial>(x->roof_material());
    bld.generated = x->generated();
}

}  // namespace

// A generous upper bound of the encoded size (points, a table per object, vectors, strings).
// The builder reserves this once: it grows by half its size at a time, and each growth copies
// the buffer while the old one is still held (over twice the scene's size at the copy).
// An unused tail costs nothing resident (the builder writes from the end down and never
// touches it). A wrong bound costs only memory: the builder still grows when it must.
size_t encoded_size_bound(const Scene& scene) {
    constexpr size_t kTable = 160, kVector = 16, kPoint2 = 8, kPoint3 = 12;
    auto ring_bytes = [&](const std::vector<Vec2>& r) { return kTable + kVector + kPoint2 * r.size(); };
    size_t n = 1 << 16;
    for (const auto& [k, v] : scene.header.options) n += kTable + 2 * kVector + k.size() + v.size();
    for (const Building& x : scene.buildings) {
        n += kTable + 3 * kVector + x.type.size() + ring_bytes(x.outer);
        for (const Ring& r : x.holes) n += 4 + ring_bytes(r);
        for (const RoofFace& f : x.roof_faces) n += 4 + kTable + kVector + kPoint3 * f.points.size();
    }
    for (const RoadEdge& x : scene.roads) n += 4 + kTable + 2 * kVector + kPoint2 * (x.quad.size() + x.centreline.size());
    for (const Joint& x : scene.joints) n += 4 + kTable + 2 * kVector + kPoint2 * x.polygon.size() + 4 * x.edges.size();
    for (const Sidewalk& x : scene.sidewalks) n += 4 + kTable + kVector + kPoint2 * x.polygon.size();
    n += (4 + kTable) * scene.lamps.size() + 64 * scene.trees.size() + (4 + kTable) * scene.crossings.size();
    n += kTable + kVector + 4 * scene.terrain.heights.size() + scene.terrain.vertical_datum.size();
    for (const LandCover& x : scene.land_cover) {
        n += 4 + kTable + kVector + ring_bytes(x.outer);
        for (const Ring& r : x.holes) n += 4 + ring_bytes(r);
    }
    for (const PathEdge& x : scene.paths) n += 4 + kTable + 2 * kVector + kPoint2 * (x.quad.size() + x.centreline.size());
    for (const Joint& x : scene.path_joints) n += 4 + kTable + 2 * kVector + kPoint2 * x.polygon.size() + 4 * x.edges.size();
    for (const RetainingWall& x : scene.retaining_walls) n += 4 + kTable + kVector + kPoint2 * x.line.size();
    return std::min<size_t>(n, FLATBUFFERS_MAX_BUFFER_SIZE / 2);
}

namespace {

// The header, with the bounds it has now (SceneEncoder::finish writes the final ones).
flatbuffers::Offset<fb::Header> encode_header(Builder& b, const SceneHeader& h) {
    // Every nested object is created into a named offset first, in a fixed order: the order in
    // which a compiler evaluates function arguments is unspecified (gcc goes right to left,
    // clang left to right), and it decides the bytes. The order below is gcc's, so scenes
    // written before this stayed byte-identical.
    std::vector<flatbuffers::Offset<fb::KeyValue>> options;
    for (const auto& [k, v] : h.options) {
        const auto value = b.CreateString(v);
        const auto key = b.CreateString(k);
        options.push_back(fb::CreateKeyValue(b, key, value));
    }
    fb::Vec2 bmin = to_fb(h.bounds_min), bmax = to_fb(h.bounds_max);
    const auto source = b.CreateString(h.source);
    const auto option_vector = b.CreateVector(options);
    const auto projection = b.CreateString(h.projection);
    const auto generator = b.CreateString(h.generator);
    return fb::CreateHeader(b, h.format_major, h.format_minor, generator,
                            h.origin_lat, h.origin_lon, projection,
                            &bmin, &bmax, h.seed, option_vector,
                            source);
}

flatbuffers::Offset<fb::Building> encode_building(Builder& b, const Building& x) {
    std::vector<flatbuffers::Offset<fb::Ring>> holes;
    for (const Ring& r : x.holes) holes.push_back(ring(b, r));
    fb::OsmRef osm = to_fb(x.osm);
    const auto type = b.CreateString(x.type);
    const auto hole_vector = b.CreateVector(holes);
    const auto outer = ring(b, x.outer);
    const auto roof_faces = encode_roof_faces(b, x.roof_faces);
    return fb::CreateBuilding(
        b, &osm, outer, hole_vector, static_cast<float>(x.min_height),
        static_cast<float>(x.height), static_cast<int16_t>(x.levels),
        static_cast<fb::HeightSource>(x.height_source), type, x.is_part,
        static_cast<fb::RoofShape>(x.roof_shape), static_cast<float>(x.roof_height), x.roof_inferred,
        roof_faces, static_cast<fb::HeightRule>(x.height_rule), x.wall_colour, x.roof_colour,
        x.colour_inferred, static_cast<fb::WallMaterial>(x.wall_material),
        static_cast<fb::RoofMaterial>(x.roof_material), x.generated);
}

// Frees a part of the scene once it is encoded, when the encoder was asked to (a const scene
// is only read).
template <typename T>
void release_part(std::vector<T>& part, bool release) {
    if (release) std::vector<T>().swap(part);
}
template <typename T>
void release_part(const std::vector<T>&, bool) {}

// Each part of the scene in the order of the file; the buildings are encoded as they come.
std::vector<flatbuffers::Offset<fb::RoadEdge>> encode_roads(Builder& b, const std::vector<RoadEdge>& items) {
    std::vector<flatbuffers::Offset<fb::RoadEdge>> roads;
    for (const RoadEdge& x : items) {
        fb::OsmRef osm = to_fb(x.osm);
        const auto quad = points(b, x.quad);
        const auto centreline = points(b, x.centreline);
        roads.push_back(fb::CreateRoadEdge(
            b, &osm, x.from_node, x.to_node, centreline, quad,
            static_cast<float>(x.width), static_cast<fb::RoadClass>(x.road_class),
            static_cast<uint8_t>(x.lanes), x.oneway, x.bridge, x.from_joint, x.to_joint,
            x.sidewalk_left, x.sidewalk_right, static_cast<uint8_t>(x.lanes_forward),
            static_cast<uint8_t>(x.lanes_backward), static_cast<fb::CentreLine>(x.centre_line), x.edge_lines,
            x.cycle_lane_left, x.cycle_lane_right));
    }
    return roads;
}

std::vector<flatbuffers::Offset<fb::Joint>> encode_joints(Builder& b, const std::vector<Joint>& items) {
    std::vector<flatbuffers::Offset<fb::Joint>> joints;
    for (const Joint& x : items) {
        fb::OsmRef osm = to_fb(x.osm);
        const auto edges = b.CreateVector(x.edges);
        const auto polygon = points(b, x.polygon);
        joints.push_back(
            fb::CreateJoint(b, &osm, polygon, edges));
    }
    return joints;
}

std::vector<flatbuffers::Offset<fb::Sidewalk>> encode_sidewalks(Builder& b, const std::vector<Sidewalk>& items) {
    std::vector<flatbuffers::Offset<fb::Sidewalk>> sidewalks;
    for (const Sidewalk& x : items)
        sidewalks.push_back(fb::CreateSidewalk(b, static_cast<fb::SidewalkKind>(x.kind),
                                               points(b, x.polygon), x.road, x.joint,
                                               static_cast<float>(x.curb_height)));
    return sidewalks;
}

std::vector<flatbuffers::Offset<fb::Lamp>> encode_lamps(Builder& b, const std::vector<Lamp>& items) {
    std::vector<flatbuffers::Offset<fb::Lamp>> lamps;
    for (const Lamp& x : items) {
        fb::OsmRef osm = to_fb(x.osm);
        fb::Vec3 pos = to_fb(x.position);
        lamps.push_back(fb::CreateLamp(b, &osm, &pos, static_cast<float>(x.height),
                                       static_cast<fb::LampSource>(x.source)));
    }
    return lamps;
}

std::vector<flatbuffers::Offset<fb::LandCover>> encode_land_cover(Builder& b, const std::vector<LandCover>& items) {
    std::vector<flatbuffers::Offset<fb::LandCover>> land_cover;
    for (const LandCover& x : items) {
        std::vector<flatbuffers::Offset<fb::Ring>> holes;
        for (const Ring& r : x.holes) holes.push_back(ring(b, r));
        fb::OsmRef osm = to_fb(x.osm);
        const auto hole_vector = b.CreateVector(holes);
        const auto outer = ring(b, x.outer);
        land_cover.push_back(fb::CreateLandCover(b, &osm, static_cast<fb::LandCoverClass>(x.cover), outer, hole_vector));
    }
    return land_cover;
}

std::vector<flatbuffers::Offset<fb::PathEdge>> encode_paths(Builder& b, const std::vector<PathEdge>& items) {
    std::vector<flatbuffers::Offset<fb::PathEdge>> paths;
    for (const PathEdge& x : items) {
        fb::OsmRef osm = to_fb(x.osm);
        const auto quad = points(b, x.quad);
        const auto centreline = points(b, x.centreline);
        // Fields in CreatePathEdge's order; `bridge` only when set (it is set only on a height
        // field), so a scene without one keeps the bytes it had before the field existed.
        fb::PathEdgeBuilder p(b);
        p.add_to_node(x.to_node);
        p.add_from_node(x.from_node);
        p.add_to_joint(x.to_joint);
        p.add_from_joint(x.from_joint);
        p.add_width(static_cast<float>(x.width));
        p.add_quad(quad);
        p.add_centreline(centreline);
        p.add_osm(&osm);
        if (x.bridge) p.add_bridge(true);
        p.add_sidewalk(x.sidewalk);
        p.add_path_class(static_cast<fb::PathClass>(x.path_class));
        paths.push_back(p.Finish());
    }
    return paths;
}

std::vector<flatbuffers::Offset<fb::Crossing>> encode_crossings(Builder& b, const std::vector<Crossing>& items) {
    std::vector<flatbuffers::Offset<fb::Crossing>> crossings;
    for (const Crossing& x : items) {
        fb::OsmRef osm = to_fb(x.osm);
        fb::Vec2 pos = to_fb(x.position);
        crossings.push_back(fb::CreateCrossing(b, &osm, x.road, &pos, static_cast<fb::CrossingKind>(x.kind),
                                               static_cast<fb::RoadSide>(x.side)));
    }
    return crossings;
}

// Absent (a null offset) for an empty field: a scene without a DEM keeps format 1.1's bytes.
flatbuffers::Offset<fb::HeightField> encode_terrain(Builder& b, const HeightField& t) {
    if (t.empty()) return 0;
    const auto datum = b.CreateString(t.vertical_datum);
    const auto heights = b.CreateVector(t.heights);
    return fb::CreateHeightField(b, t.origin.x, t.origin.y, t.cell, t.nx, t.ny, heights, t.reference_altitude, datum);
}

// Absent (a null offset) when there are none: a scene without a field keeps its bytes.
flatbuffers::Offset<flatbuffers::Vector<flatbuffers::Offset<fb::RetainingWall>>> encode_retaining_walls(
    Builder& b, const std::vector<RetainingWall>& items) {
    if (items.empty()) return 0;
    std::vector<flatbuffers::Offset<fb::RetainingWall>> walls;
    for (const RetainingWall& x : items) {
        fb::OsmRef osm = to_fb(x.osm);
        const auto line = points(b, x.line);
        walls.push_back(fb::CreateRetainingWall(b, &osm, line, static_cast<float>(x.height), x.height_tagged,
                                                static_cast<fb::WallMaterial>(x.material)));
    }
    return b.CreateVector(walls);
}

std::vector<fb::Tree> encode_trees(const std::vector<Tree>& items) {
    std::vector<fb::Tree> trees;
    trees.reserve(items.size());
    for (const Tree& x : items)
        trees.emplace_back(static_cast<float>(x.position.x), static_cast<float>(x.position.y),
                           static_cast<float>(x.height), static_cast<float>(x.crown_diameter), x.osm.id,
                           static_cast<fb::OsmType>(x.osm.type), static_cast<fb::LeafType>(x.leaf_type),
                           static_cast<fb::TreeSource>(x.source));
    return trees;
}

}  // namespace

struct SceneEncoder::State {
    explicit State(size_t reserve) : b(reserve) {}
    Builder b;
    flatbuffers::Offset<fb::Header> header;
    std::vector<flatbuffers::Offset<fb::Building>> buildings;
};

SceneEncoder::SceneEncoder(const SceneHeader& header, size_t reserve) : state_(std::make_unique<State>(reserve)) {
    state_->b.ForceDefaults(true);  // a field equal to its default is still written: stable layout
    state_->header = encode_header(state_->b, header);
}

SceneEncoder::~SceneEncoder() = default;

void SceneEncoder::add_building(const Building& building) {
    state_->buildings.push_back(encode_building(state_->b, building));
}

void SceneEncoder::finish(const Scene& scene) { finish_parts(scene, false); }

void SceneEncoder::finish_releasing(Scene& scene) { finish_parts(scene, true); }

template <typename S>
void SceneEncoder::finish_parts(S& scene, bool release) {
    Builder& b = state_->b;
    // The header was written first, with the bounds known then: now the final ones, in place.
    fb::Header* header = flatbuffers::GetMutableTemporaryPointer(b, state_->header);
    *const_cast<fb::Vec2*>(header->bounds_min()) = to_fb(scene.header.bounds_min);
    *const_cast<fb::Vec2*>(header->bounds_max()) = to_fb(scene.header.bounds_max);

    const auto roads = encode_roads(b, scene.roads);
    release_part(scene.roads, release);

    const auto joints = encode_joints(b, scene.joints);
    release_part(scene.joints, release);

    const auto sidewalks = encode_sidewalks(b, scene.sidewalks);
    release_part(scene.sidewalks, release);

    const auto lamps = encode_lamps(b, scene.lamps);
    release_part(scene.lamps, release);
    fb::Vec2 gmin = to_fb(scene.ground.min), gmax = to_fb(scene.ground.max);
    auto ground = fb::CreateGround(b, &gmin, &gmax, static_cast<float>(scene.ground.z));

    const auto land_cover = encode_land_cover(b, scene.land_cover);
    release_part(scene.land_cover, release);

    const auto trees = encode_trees(scene.trees);
    release_part(scene.trees, release);

    const auto paths = encode_paths(b, scene.paths);
    release_part(scene.paths, release);
    const auto path_joints = encode_joints(b, scene.path_joints);
    release_part(scene.path_joints, release);

    const auto crossings = encode_crossings(b, scene.crossings);
    release_part(scene.crossings, release);

    const auto terrain = encode_terrain(b, scene.terrain);
    release_part(scene.terrain.heights, release);

    const auto retaining_walls = encode_retaining_walls(b, scene.retaining_walls);
    release_part(scene.retaining_walls, release);

    const auto crossing_vector = b.CreateVector(crossings);
    const auto path_joint_vector = b.CreateVector(path_joints);
    const auto path_vector = b.CreateVector(paths);
    const auto tree_vector = b.CreateVectorOfStructs(trees);
    const auto land_cover_vector = b.CreateVector(land_cover);
    const auto lamp_vector = b.CreateVector(lamps);
    const auto sidewalk_vector = b.CreateVector(sidewalks);
    const auto joint_vector = b.CreateVector(joints);
    const auto road_vector = b.CreateVector(roads);
    const auto building_vector = b.CreateVector(state_->buildings);
    auto root = fb::CreateScene(b, state_->header, building_vector, road_vector, joint_vector, sidewalk_vector, lamp_vector,
                                ground, land_cover_vector, tree_vector, path_vector, path_joint_vector,
                                crossing_vector, terrain, retaining_walls);
    fb::FinishSceneBuffer(b, root);
}

const uint8_t* SceneEncoder::data() const { return state_->b.GetBufferPointer(); }
size_t SceneEncoder::size() const { return state_->b.GetSize(); }

namespace {

// The whole scene at once; nothing is freed.
void encode_into(const Scene& scene, SceneEncoder& encoder) {
    for (const Building& b : scene.buildings) encoder.add_building(b);
    encoder.finish(scene);
}

}  // namespace

std::vector<uint8_t> encode_scene(const Scene& scene) {
    SceneEncoder encoder(scene.header, encoded_size_bound(scene));
    encode_into(scene, encoder);
    return {encoder.data(), encoder.data() + encoder.size()};
}

namespace {

// The header: format, origin, bounds, seed and the options the parse ran with.
void decode_header(const fb::Scene* in, Checker& check, Scene& s) {
    SceneHeader& out = s.header;
    const fb::Header* h = in->header();
    out.format_major = h->format_major();
    out.format_minor = h->format_minor();
    out.generator = str(h->generator());
    out.origin_lat = h->origin_lat();
    out.origin_lon = h->origin_lon();
    if (!std::isfinite(out.origin_lat) || !std::isfinite(out.origin_lon) ||
        std::fabs(out.origin_lat) > 90 || std::fabs(out.origin_lon) > 180)
        check.fail("origin is not a valid latitude/longitude");
    out.projection = str(h->projection());
    out.bounds_min = check.vec(h->bounds_min(), "header bounds");
    out.bounds_max = check.vec(h->bounds_max(), "header bounds");
    out.seed = h->seed();
    if (h->options())
        for (const fb::KeyValue* kv : *h->options())
            out.options.emplace_back(str(kv->key()), str(kv->value()));
    out.source = str(h->source());
}

void decode_buildings(const fb::Scene* in, Checker& check, Scene& s) {
    if (in->buildings())
        for (const fb::Building* x : *in->buildings()) {
            Building bld;
            bld.osm = check.osm(x->osm());
            bld.outer = check.ring(x->outer(), "building outline");
            check.area_ring(bld.outer, "building outline");
            if (x->holes())
                for (const fb::Ring* r : *x->holes()) {
                    bld.holes.push_back(check.ring(r, "building hole"));
                    check.area_ring(bld.holes.back(), "building hole");
                }
            bld.min_height = check.height(x->min_height(), "building min_height");
            bld.height = check.height(x->height(), "building height");
            bld.levels = x->levels();
            if (x->height_source() > fb::HeightSource::MAX) check.fail("invalid height source");
            bld.height_source = static_cast<HeightSource>(x->height_source());
            bld.type = str(x->type());
            bld.is_part = x->is_part();
            decode_building_look(x, check, bld);
            s.buildings.push_back(std::move(bld));
        }
}

void decode_roads(const fb::Scene* in, Checker& check, Scene& s) {
    const size_t joint_count = in->joints() ? in->joints()->size() : 0;
    if (in->roads())
        for (const fb::RoadEdge* x : *in->roads()) {
            RoadEdge r;
            r.osm = check.osm(x->osm());
            r.from_node = x->from_node();
            r.to_node = x->to_node();
            r.centreline = check.pts(x->centreline(), "road centreline");
            r.quad = check.pts(x->quad(), "road quadrangle");
            r.width = check.height(x->width(), "road width");
            if (x->road_class() > fb::RoadClass::MAX) check.fail("invalid road class");
            r.road_class = static_cast<RoadClass>(x->road_class());
            r.lanes = x->lanes();
            r.oneway = x->oneway();
            r.bridge = x->bridge();
            r.from_joint = check.index(x->from_joint(), joint_count, "road joint");
            r.to_joint = check.index(x->to_joint(), joint_count, "road joint");
            r.sidewalk_left = x->sidewalk_left();
            r.sidewalk_right = x->sidewalk_right();
            r.lanes_forward = x->lanes_forward();
            r.lanes_backward = x->lanes_backward();
            if (x->centre_line() > fb::CentreLine::MAX) check.fail("invalid centre line");
            r.centre_line = static_cast<CentreLine>(x->centre_line());
            r.edge_lines = x->edge_lines();
            r.cycle_lane_left = x->cycle_lane_left();
            r.cycle_lane_right = x->cycle_lane_right();
            s.roads.push_back(std::move(r));
        }
}

void decode_joints(const fb::Scene* in, Checker& check, Scene& s) {
    const size_t road_count = in->roads() ? in->roads()->size() : 0;
    if (in->joints())
        for (const fb::Joint* x : *in->joints()) {
            Joint j;
            j.osm = check.osm(x->osm());
            j.polygon = check.pts(x->polygon(), "joint polygon");
            if (x->edges())
                for (uint32_t e : *x->edges()) {
                    if (e >= road_count) check.fail("joint edge index " + std::to_string(e) + " out of range");
                    j.edges.push_back(e);
                }
            s.joints.push_back(std::move(j));
        }
}

void decode_sidewalks(const fb::Scene* in, Checker& check, Scene& s) {
    const size_t road_count = in->roads() ? in->roads()->size() : 0;
    const size_t joint_count = in->joints() ? in->joints()->size() : 0;
    if (in->sidewalks())
        for (const fb::Sidewalk* x : *in->sidewalks()) {
            Sidewalk w;
            if (x->kind() > fb::SidewalkKind::MAX) check.fail("invalid sidewalk kind");
            w.kind = static_cast<SidewalkKind>(x->kind());
            w.polygon = check.pts(x->polygon(), "sidewalk polygon");
            w.road = check.index(x->road(), road_count, "sidewalk road");
            w.joint = check.index(x->joint(), joint_count, "sidewalk joint");
            w.curb_height = check.height(x->curb_height(), "sidewalk curb height");
            s.sidewalks.push_back(std::move(w));
        }
}

void decode_lamps(const fb::Scene* in, Checker& check, Scene& s) {
    if (in->lamps())
        for (const fb::Lamp* x : *in->lamps()) {
            Lamp l;
            l.osm = check.osm(x->osm());
            if (!x->position()) check.fail("lamp without position");
            l.position = {check.coordinate(x->position()->x(), "lamp position"),
                          check.coordinate(x->position()->y(), "lamp position"),
                          check.coordinate(x->position()->z(), "lamp position")};
            l.height = check.height(x->height(), "lamp height");
            if (x->source() > fb::LampSource::MAX) check.fail("invalid lamp source");
            l.source = static_cast<LampSource>(x->source());
            s.lamps.push_back(l);
        }
}

void decode_ground(const fb::Scene* in, Checker& check, Scene& s) {
    if (const fb::Ground* g = in->ground()) {
        // The ground reaches a margin beyond the objects.
        for (const fb::Vec2* p : {g->min(), g->max()}) {
            if (!p) check.fail("missing point in ground");
            check.coordinate(p->x(), "ground", 2 * kMaxCoordinate);
            check.coordinate(p->y(), "ground", 2 * kMaxCoordinate);
        }
        s.ground.min = {g->min()->x(), g->min()->y()};
        s.ground.max = {g->max()->x(), g->max()->y()};
        s.ground.z = check.coordinate(g->z(), "ground");
    }
}

void decode_land_cover(const fb::Scene* in, Checker& check, Scene& s) {
    if (in->land_cover())
        for (const fb::LandCover* x : *in->land_cover()) {
            LandCover c;
            c.osm = check.osm(x->osm());
            if (x->cover() > fb::LandCoverClass::MAX) check.fail("invalid land cover class");
            c.cover = static_cast<LandCoverClass>(x->cover());
            c.outer = check.ring(x->outer(), "land cover outline", kMaxLandCoverPoints, kMaxLandCoverExtent);
            check.area_ring(c.outer, "land cover outline");
            if (x->holes())
                for (const fb::Ring* r : *x->holes()) {
                    c.holes.push_back(check.ring(r, "land cover hole", kMaxLandCoverPoints, kMaxLandCoverExtent));
                    check.area_ring(c.holes.back(), "land cover hole");
                }
            s.land_cover.push_back(std::move(c));
        }
}

void decode_trees(const fb::Scene* in, Checker& check, Scene& s) {
    // The verifier aligns a vector of structs to 4 bytes only; a Tree holds a long and needs 8.
    if (in->trees() && in->trees()->size() > 0 &&
        reinterpret_cast<uintptr_t>(in->trees()->Data()) % alignof(fb::Tree) != 0)
        check.fail("corrupt scene (misaligned tree list)");
    if (in->trees())
        for (const fb::Tree* x : *in->trees()) {
            Tree t;
            if (x->osm_type() > fb::OsmType::MAX) check.fail("invalid OSM object type");
            if (x->leaf_type() > fb::LeafType::MAX) check.fail("invalid leaf type");
            if (x->source() > fb::TreeSource::MAX) check.fail("invalid tree source");
            t.osm = {static_cast<OsmType>(x->osm_type()), x->osm_id()};
            t.position = {check.coordinate(x->x(), "tree position"), check.coordinate(x->y(), "tree position")};
            t.height = check.height(x->height(), "tree height");
            t.crown_diameter = check.height(x->crown_diameter(), "tree crown");
            if (!(t.height > 0) || !(t.crown_diameter > 0)) check.fail("tree with non-positive size");
            t.leaf_type = static_cast<LeafType>(x->leaf_type());
            t.source = static_cast<TreeSource>(x->source());
            s.trees.push_back(t);
        }
}

// Paths and rails with their joints.
void decode_paths(const fb::Scene* in, Checker& check, Scene& s) {
    const size_t path_count = in->paths() ? in->paths()->size() : 0;
    const size_t path_joint_count = in->path_joints() ? in->path_joints()->size() : 0;
    if (in->paths())
        for (const fb::PathEdge* x : *in->paths()) {
            PathEdge p;
            p.osm = check.osm(x->osm());
            p.from_node = x->from_node();
            p.to_node = x->to_node();
            p.centreline = check.pts(x->centreline(), "path centreline");
            p.quad = check.pts(x->quad(), "path quadrangle");
            if (p.centreline.size() < 2 || p.quad.size() != 4) check.fail("path without centreline or quadrangle");
            p.width = check.height(x->width(), "path width");
            if (x->path_class() > fb::PathClass::MAX) check.fail("invalid path class");
            p.path_class = static_cast<PathClass>(x->path_class());
            p.from_joint = check.index(x->from_joint(), path_joint_count, "path joint");
            p.to_joint = check.index(x->to_joint(), path_joint_count, "path joint");
            p.sidewalk = x->sidewalk();
            p.bridge = x->bridge();
            s.paths.push_back(std::move(p));
        }
    if (in->path_joints())
        for (const fb::Joint* x : *in->path_joints()) {
            Joint j;
            j.osm = check.osm(x->osm());
            j.polygon = check.pts(x->polygon(), "path joint polygon");
            if (x->edges())
                for (uint32_t e : *x->edges()) {
                    if (e >= path_count) check.fail("path joint edge index " + std::to_string(e) + " out of range");
                    j.edges.push_back(e);
                }
            s.path_joints.push_back(std::move(j));
        }
}

void decode_crossings(const fb::Scene* in, Checker& check, Scene& s) {
    const size_t road_count = in->roads() ? in->roads()->size() : 0;
    if (in->crossings())
        for (const fb::Crossing* x : *in->crossings()) {
            Crossing c;
            c.osm = check.osm(x->osm());
            if (x->road() < 0 || x->road() >= static_cast<int64_t>(road_count)) check.fail("crossing road index out of range");
            c.road = x->road();
            c.position = check.vec(x->position(), "crossing");
            if (x->kind() > fb::CrossingKind::MAX || x->side() > fb::RoadSide::MAX) check.fail("invalid crossing");
            c.kind = static_cast<CrossingKind>(x->kind());
            c.side = static_cast<RoadSide>(x->side());
            s.crossings.push_back(c);
        }
}

// The height field: a grid within the limits, one finite height per node, every altitude
// (reference + height) within kMinAltitude..kMaxAltitude.
void decode_terrain(const fb::Scene* in, Checker& check, Scene& s) {
    const fb::HeightField* t = in->terrain();
    if (!t) return;
    HeightField& f = s.terrain;
    f.origin = {t->origin_x(), t->origin_y()};
    f.cell = t->cell();
    f.nx = t->nx();
    f.ny = t->ny();
    if (!height_field_within_limit(f.origin, f.cell, f.nx, f.ny))
        check.fail("terrain grid of " + std::to_string(f.nx) + " x " + std::to_string(f.ny) + " nodes, cell " +
                   std::to_string(f.cell) + " m, is beyond the limits (2 x 2 to " +
                   std::to_string(kMaxHeightFieldNodes) + " nodes within the coordinate limit)");
    const size_t count = t->heights() ? t->heights()->size() : 0;
    if (count != static_cast<uint64_t>(f.nx) * f.ny)
        check.fail("terrain has " + std::to_string(count) + " heights for " + std::to_string(f.nx) + " x " +
                   std::to_string(f.ny) + " nodes");
    f.reference_altitude = t->reference_altitude();
    if (!altitude_within_limit(f.reference_altitude)) check.fail("terrain reference altitude beyond -500..9000 m");
    f.heights.reserve(count);
    for (float h : *t->heights()) {
        if (!altitude_within_limit(f.reference_altitude + h))
            check.fail("terrain height " + std::to_string(f.reference_altitude + h) + " m beyond -500..9000 m");
        f.heights.push_back(h);
    }
    f.vertical_datum = str(t->vertical_datum());
}

// Retaining walls: a line of at least two points within the object limits, a height in
// (0, kMaxHeight], a known material.
void decode_retaining_walls(const fb::Scene* in, Checker& check, Scene& s) {
    if (in->retaining_walls())
        for (const fb::RetainingWall* x : *in->retaining_walls()) {
            RetainingWall w;
            w.osm = check.osm(x->osm());
            w.line = check.pts(x->line(), "retaining wall line");
            if (w.line.size() < 2) check.fail("retaining wall with fewer than 2 points");
            w.height = check.height(x->height(), "retaining wall height");
            if (!(w.height > 0)) check.fail("retaining wall with zero height");
            w.height_tagged = x->height_tagged();
            if (x->material() > fb::WallMaterial::MAX) check.fail("invalid retaining wall material");
            w.material = static_cast<WallMaterial>(x->material());
            s.retaining_walls.push_back(std::move(w));
        }
}

}  // namespace

Scene decode_scene(const uint8_t* data, size_t size, const std::string& name) {
    Checker check{name};
    if (size == 0) check.fail("empty file, not a citygen scene");
    if (size < 8 || !fb::SceneBufferHasIdentifier(data))
        check.fail("not a citygen scene (wrong file identifier)");
    flatbuffers::Verifier verifier(data, size, 64, 100000000);
    if (!fb::VerifySceneBuffer(verifier)) check.fail("corrupt or truncated scene (verification failed)");

    const fb::Scene* in = fb::GetScene(data);
    const fb::Header* h = in->header();
    if (!h) check.fail("scene has no header");
    if (h->format_major() > kSceneFormatMajor)
        check.fail("scene format " + std::to_string(h->format_major()) + "." +
                   std::to_string(h->format_minor()) + " is newer than this program reads (" +
                   std::to_string(kSceneFormatMajor) + ".x); update citygen");

    Scene s;
    decode_header(in, check, s);
    // Each class fills its own part of the scene from the buffer alone, so they are decoded side
    // by side; of several bad parts the first in this order is the one reported, as one by one.
    using Decoder = void (*)(const fb::Scene*, Checker&, Scene&);
    static constexpr Decoder kDecoders[] = {decode_buildings, decode_roads,      decode_joints, decode_sidewalks,
                                            decode_lamps,     decode_ground,     decode_land_cover, decode_trees,
                                            decode_paths,     decode_crossings,  decode_terrain,
                                            decode_retaining_walls};
    constexpr size_t kParts = std::size(kDecoders);
    std::exception_ptr errors[kParts];
    tbb::parallel_for(size_t{0}, kParts, [&](size_t i) {
        try {
            Checker part{check.name};
            kDecoders[i](in, part, s);
        } catch (...) {
            errors[i] = std::current_exception();
        }
    });
    for (const std::exception_ptr& error : errors)
        if (error) std::rethrow_exception(error);
    return s;
}

void check_scene_loads(const uint8_t* data, size_t size, const std::string& name) {
    try {
        decode_scene(data, size, name);
    } catch (const Error& e) {
        throw Error(std::string(e.what()) + " (not written: the scene loader would refuse it)");
    }
}

Scene load_scene(const std::string& path) {
    // Non-blocking: a FIFO is refused below rather than waited on.
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
    if (fd < 0) throw Error(path + ": cannot open scene file (" + std::strerror(errno) + ")");
    struct Close {
        int fd;
        ~Close() { ::close(fd); }
    } close_file{fd};
    struct stat info;
    if (::fstat(fd, &info) != 0 || !S_ISREG(info.st_mode))
        throw Error(path + ": not a regular file (a directory, device or pipe cannot be a scene)");
    const size_t size = static_cast<size_t>(info.st_size);
    if (size == 0) return decode_scene(nullptr, 0, path);  // its one line for an empty file
    // The file's pages mapped whole and at once (a metropolis's scene is hundreds of MB): no
    // zeroed buffer to fill, no copy, and no page fault per page while decoding.
    void* bytes = ::mmap(nullptr, size, PROT_READ, MAP_PRIVATE | MAP_POPULATE, fd, 0);
    if (bytes == MAP_FAILED) throw Error(path + ": cannot read scene file (" + std::strerror(errno) + ")");
    struct Unmap {
        void* p;
        size_t n;
        ~Unmap() { ::munmap(p, n); }
    } unmap{bytes, size};
    return decode_scene(static_cast<const uint8_t*>(bytes), size, path);
}

void write_file_atomically(const std::string& path, const void* data, size_t size,
                           const std::function<void()>& check) {
    check_output_target(path);  // the rename would replace a symlink, FIFO or device node
    const std::string tmp = path + ".tmp" + std::to_string(::getpid());
    std::string failure;  // why the temporary file could not be written, or empty
    auto write_tmp = [&] {
        FILE* f = std::fopen(tmp.c_str(), "wb");
        if (!f) {
            failure = std::strerror(errno);
            return;
        }
        bool ok = std::fwrite(data, 1, size, f) == size;
        ok = (std::fflush(f) == 0) && ok;
        ok = (::fsync(::fileno(f)) == 0) && ok;
        ok = (std::fclose(f) == 0) && ok;
        if (!ok) failure = std::strerror(errno);
    };
    std::exception_ptr check_error;
    if (check) {
        std::thread writer(write_tmp);
        try {
            check();
        } catch (...) {
            check_error = std::current_exception();
        }
        writer.join();
    } else {
        write_tmp();
    }
    if (check_error || !failure.empty() || std::rename(tmp.c_str(), path.c_str()) != 0) {
        if (failure.empty()) failure = std::strerror(errno);
        std::remove(tmp.c_str());
        if (check_error) std::rethrow_exception(check_error);
        throw Error(path + ": cannot write (" + failure + ")");
    }
}

void save_scene(const Scene& scene, const std::string& path) {
    SceneEncoder encoder(scene.header, encoded_size_bound(scene));
    encode_into(scene, encoder);
    write_file_atomically(path, encoder.data(), encoder.size());  // no copy of the bytes
}

}  // namespace citygen
