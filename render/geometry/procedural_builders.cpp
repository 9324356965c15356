// The procedural builders: the same surfaces as the stored builders (stored_buildings.cpp,
// stored_flat_polygons.cpp), as user-geometry primitives instead of triangles.
#include <algorithm>
#include <memory>
#include <vector>

#include <tbb/parallel_for.h>

#include "render/facade/facade_materials.h"
#include "render/geometry/bridge_geometry.h"
#include "render/geometry/ground.h"
#include "render/geometry/procedural_geometry.h"
#include "render/geometry/stored_geometry.h"
#include "render/materials/materials.h"

namespace citygen {

namespace {

ProceduralGeometry::SurfaceMaterials all_surfaces(uint16_t material) {
    ProceduralGeometry::SurfaceMaterials m;
    m.fill(material);
    return m;
}

}  // namespace

void add_ground_polygon(const Scene& scene, const Ring& outer, const std::vector<Ring>& holes, double lift,
                        uint32_t object, uint16_t material, ProceduralGeometry& geometry) {
    if (scene.terrain.empty()) {
        geometry.add_polygon(object, outer, holes, scene.ground.z + lift, material);
        return;
    }
    const DrapedPolygon draped = drape_polygon(scene, outer, holes, lift);
    for (const auto& t : draped.triangles)
        geometry.add_face(object, {draped.points[t[0]], draped.points[t[1]], draped.points[t[2]]}, material);
}

namespace {

// Buildings [begin, end) into `geometry`, in order.
void add_procedural_buildings(const Scene& scene, const FacadeOptions& facades, uint32_t begin, uint32_t end,
                              ProceduralGeometry& geometry, Progress* progress) {
    for (uint32_t index = begin; index < end; ++index) {
        if (progress) progress->advance();
        const Building& b = scene.buildings[index];
        if (!has_volume(b)) continue;
        const double ground = building_base(scene, b);
        const double bottom = ground + b.min_height, top = ground + b.height;
        const BuildingWalls walls(b);
        const WallInput first = walls.input(0);
        const FacadeChoices choices = facade_choices(facades, first.building_key, first.style);
        uint32_t choices_index = 0;  // added with the building's first wall that has windows
        bool choices_added = false;
        for (size_t w = 0, n = walls.count(); w < n; ++w) {
            Vec2 p, q;
            walls.wall(w, &p, &q);
            const WallInput input = walls.input(w);
            if (p == q || !(input.height > 0)) continue;  // no wall under a roof that starts at the bottom
            const WallGrid grid = wall_grid(facades, choices, input);
            if (!grid.plain() && !choices_added) {
                choices_index = geometry.add_facade_choices(choices);
                choices_added = true;
            }
            geometry.add_wall(index, input, choices_index, grid, p, q, bottom);
        }
        if (b.roof_faces.empty()) geometry.add_polygon(index, b.outer, b.holes, top, kRoof, +1);
        for (const RoofFace& face : b.roof_faces)
            geometry.add_face(index, lifted_face(face, ground), roof_face_material(face));
        if (b.min_height > 0) geometry.add_polygon(index, b.outer, b.holes, bottom, kFacade, -1);
    }
}

}  // namespace

std::unique_ptr<ProceduralGeometry> build_procedural_buildings(const Scene& scene, const FacadeOptions& facades,
                                                               Progress* progress) {
    auto geometry = std::make_unique<ProceduralGeometry>(ObjectKind::Building, facade_surface_materials());
    size_t walls = 0;
    for (const Building& b : scene.buildings)
        if (has_volume(b)) walls += building_wall_count(b);
    geometry->reserve_walls(walls);
    // Runs of buildings are made side by side and joined in order, a batch of runs at a time (all
    // of a metropolis's at once would hold its walls twice).
    constexpr uint32_t kBuildingsPerRun = 1024;
    constexpr size_t kRunsPerBatch = 32;
    const auto n = static_cast<uint32_t>(scene.buildings.size());
    const size_t runs = (n + kBuildingsPerRun - 1) / kBuildingsPerRun;
    std::vector<std::unique_ptr<ProceduralGeometry>> parts(std::min(runs, kRunsPerBatch));
    for (size_t first = 0; first < runs; first += kRunsPerBatch) {
        const size_t count = std::min(kRunsPerBatch, runs - first);
        tbb::parallel_for(size_t{0}, count, [&](size_t i) {
            const auto begin = static_cast<uint32_t>((first + i) * kBuildingsPerRun);
            parts[i] = std::make_unique<ProceduralGeometry>(ObjectKind::Building, facade_surface_materials());
            add_procedural_buildings(scene, facades, begin, std::min(n, begin + kBuildingsPerRun), *parts[i], progress);
        });
        for (size_t i = 0; i < count; ++i) {
            geometry->append(*parts[i]);
            parts[i].reset();
        }
    }
    return geometry;
}

std::unique_ptr<ProceduralGeometry> build_procedural_roads(const Scene& scene) {
    auto geometry = std::make_unique<ProceduralGeometry>(ObjectKind::Road, all_surfaces(kAsphalt));
    const std::vector<DeckLine> decks = drawn_decks(scene);
    for (uint32_t i = 0; i < scene.roads.size(); ++i) {
        if (i < decks.size() && decks[i].valid) {
            add_faces(deck_piece_faces(edge_deck(decks, i), scene.roads[i].quad, kRoadLift, kAsphalt), i, *geometry);
            add_faces(deck_piers(scene, decks[i], scene.roads[i].width), i, *geometry);
            continue;
        }
        add_ground_polygon(scene, scene.roads[i].quad, {}, kRoadLift, i, kAsphalt, *geometry);
    }
    return geometry;
}

std::unique_ptr<ProceduralGeometry> build_procedural_joints(const Scene& scene) {
    auto geometry = std::make_unique<ProceduralGeometry>(ObjectKind::Joint, all_surfaces(kAsphalt));
    const std::vector<DeckLine> decks = drawn_decks(scene);
    for (uint32_t i = 0; i < scene.joints.size(); ++i) {
        if (const DeckSurface deck = joint_deck(scene, decks, scene.joints[i]); deck.valid()) {
            add_faces(deck_piece_faces(deck, scene.joints[i].polygon, kRoadLift, kAsphalt), i, *geometry);
            continue;
        }
        add_ground_polygon(scene, scene.joints[i].polygon, {}, kRoadLift, i, kAsphalt, *geometry);
    }
    return geometry;
}

std::unique_ptr<ProceduralGeometry> build_procedural_sidewalks(const Scene& scene) {
    auto geometry = std::make_unique<ProceduralGeometry>(ObjectKind::Sidewalk, all_surfaces(kCurb));
    SidewalkShape shape;
    const std::vector<DeckLine> decks = drawn_decks(scene);
    for (uint32_t i = 0; i < scene.sidewalks.size(); ++i) {
        if (!sidewalk_shape(scene, i, &shape)) continue;
        if (const DeckSurface deck = sidewalk_deck(scene, decks, scene.sidewalks[i]); deck.valid()) {
            add_faces(deck_piece_faces(deck, shape.ring, kRoadLift + (shape.top_z - shape.road_z), kSidewalk), i,
                      *geometry);
            continue;
        }
        if (!scene.terrain.empty()) {
            add_ground_polygon(scene, shape.ring, {}, kRoadLift + (shape.top_z - shape.road_z), i, kSidewalk,
                               *geometry);
            for (const CurbFace& f : draped_curb_faces(scene, shape))
                geometry->add_face(i, {f[0], f[1], f[2], f[3]}, kCurb);
            continue;
        }
        if (shape.has_curb()) geometry->add_curbed_polygon(i, shape.ring, shape.top_z, kSidewalk, shape.road_z);
        else geometry->add_polygon(i, shape.ring, {}, shape.top_z, kSidewalk);
    }
    return geometry;
}

std::unique_ptr<ProceduralGeometry> build_procedural_terrain(const Scene& scene) {
    auto geometry = std::make_unique<ProceduralGeometry>(ObjectKind::Terrain, all_surfaces(kGround));
    const Box2 e = terrain_extent(scene);
    geometry->add_polygon(0, Ring{e.min, {e.max.x, e.min.y}, e.max, {e.min.x, e.max.y}}, {}, scene.ground.z, kGround);
    return geometry;
}

}  // namespace citygen
