#include "render/geometry/path_geometry.h"

#include <cmath>

#include "render/geometry/bridge_geometry.h"
#include "render/geometry/road_markings.h"
#include "render/geometry/stair_geometry.h"
#include "render/geometry/stored_geometry.h"
#include "render/geometry/surface_detail.h"
#include "render/materials/materials.h"

namespace citygen {

namespace {

uint16_t joint_material(const Scene& scene, const Joint& j) {
    return j.edges.empty() ? static_cast<uint16_t>(kPathPaving) : path_material(scene.paths[j.edges.front()].path_class);
}

ProceduralGeometry::SurfaceMaterials walls() {
    ProceduralGeometry::SurfaceMaterials m;
    m.fill(kPathPaving);
    return m;
}

// A path on the ground, draped or as a stair (stair_geometry.h), or on its deck with its slab and
// piers (bridge_geometry.h); a path joint the same, on its deck where every path meeting there is
// a bridge.
template <class Geometry>
void add_path(const Scene& scene, const std::vector<DeckLine>& decks, uint32_t i, Geometry& geometry) {
    const PathEdge& p = scene.paths[i];
    const uint16_t material = path_material(p.path_class);
    if (i < decks.size() && decks[i].valid) {
        add_faces(deck_piece_faces(edge_deck(decks, i), p.quad, path_lift(p), material), i, geometry);
        add_faces(deck_piers(scene, decks[i], p.width), i, geometry);
        return;
    }
    if (!add_stair(scene, i, path_lift(p), material, geometry))
        add_ground_polygon(scene, p.quad, {}, path_lift(p), i, material, geometry);
}

template <class Geometry>
void add_path_joint(const Scene& scene, const std::vector<DeckLine>& decks, uint32_t i, Geometry& geometry) {
    const Joint& j = scene.path_joints[i];
    if (const DeckSurface deck = path_joint_deck(scene, decks, j); deck.valid()) {
        add_faces(deck_piece_faces(deck, j.polygon, kPathLift, joint_material(scene, j)), i, geometry);
        return;
    }
    add_ground_polygon(scene, j.polygon, {}, kPathLift, i, joint_material(scene, j), geometry);
}

}  // namespace

uint16_t path_material(PathClass c) {
    switch (c) {
        case PathClass::Footway:
        case PathClass::Pedestrian:
        case PathClass::Steps: return kPathPaving;
        case PathClass::Cycleway: return kCyclewaySurface;
        case PathClass::Path:
        case PathClass::Track:
        case PathClass::Bridleway: return kGravel;
        case PathClass::Tram: return kAsphalt;  // street track: paved between the rails
        case PathClass::Rail:
        case PathClass::LightRail:
        case PathClass::Subway: return kBallast;
    }
    return kPathPaving;
}

double path_lift(const PathEdge& path) { return path.path_class == PathClass::Tram ? kTramLift : kPathLift; }

double path_z(const Scene& scene, const PathEdge& path) { return scene.ground.z + path_lift(path); }

TriangleMesh build_stored_paths(const Scene& scene) {
    TriangleMesh mesh;
    mesh.kind = ObjectKind::Path;
    const std::vector<DeckLine> decks = drawn_path_decks(scene);
    for (uint32_t i = 0; i < scene.paths.size(); ++i) add_path(scene, decks, i, mesh);
    return mesh;
}

TriangleMesh build_stored_path_joints(const Scene& scene) {
    TriangleMesh mesh;
    mesh.kind = ObjectKind::PathJoint;
    const std::vector<DeckLine> decks = drawn_path_decks(scene);
    for (uint32_t i = 0; i < scene.path_joints.size(); ++i) add_path_joint(scene, decks, i, mesh);
    return mesh;
}

std::unique_ptr<ProceduralGeometry> build_procedural_paths(const Scene& scene) {
    auto geometry = std::make_unique<ProceduralGeometry>(ObjectKind::Path, walls());
    const std::vector<DeckLine> decks = drawn_path_decks(scene);
    for (uint32_t i = 0; i < scene.paths.size(); ++i)
        if (scene.paths[i].quad.size() >= 3) add_path(scene, decks, i, *geometry);
    return geometry;
}

std::unique_ptr<ProceduralGeometry> build_procedural_path_joints(const Scene& scene) {
    auto geometry = std::make_unique<ProceduralGeometry>(ObjectKind::PathJoint, walls());
    const std::vector<DeckLine> decks = drawn_path_decks(scene);
    for (uint32_t i = 0; i < scene.path_joints.size(); ++i)
        if (scene.path_joints[i].polygon.size() >= 3) add_path_joint(scene, decks, i, *geometry);
    return geometry;
}

PathPaint path_paint(const PathEdge& path) {
    PathPaint paint;
    paint.path_class = path.path_class;
    paint.straight = path.centreline.size() >= 2;
    if (paint.straight) paint.a = path.centreline.front(), paint.b = path.centreline.back();
    return paint;
}

uint16_t path_surface_material(const PathPaint& path, Vec2 p) {
    const uint16_t base = path_material(path.path_class);
    if (!is_rail(path.path_class) || !path.straight) return base;
    const Vec2 a = path.a, d = normalize(path.b - a);
    const double along = dot(p - a, d), across = std::fabs(cross(d, p - a));
    constexpr double kHalfGauge = 0.7175 + 0.035, kRailHead = 0.035;
    if (std::fabs(across - kHalfGauge) < kRailHead) return kRailSteel;
    const double phase = along / 0.6 - std::floor(along / 0.6);
    if (path.path_class != PathClass::Tram && across < 1.3 && phase < 0.4) return kSleeper;
    return base == kAsphalt ? asphalt_grain(p) : base;
}

std::unique_ptr<RenderGeometry> with_rail_tracks(std::unique_ptr<RenderGeometry> geometry, const Scene& scene) {
    // Its own copy of what it paints from: the scene may go first.
    auto paths = std::make_shared<std::vector<PathPaint>>();
    paths->reserve(scene.paths.size());
    for (const PathEdge& p : scene.paths) paths->push_back(path_paint(p));
    return std::make_unique<SurfaceDetailGeometry>(std::move(geometry), [paths](Hit& hit) {
        if (hit.kind != ObjectKind::Path || hit.object >= paths->size()) return;
        hit.material = path_surface_material((*paths)[hit.object], {hit.position.x, hit.position.y});
    });
}

}  // namespace citygen
