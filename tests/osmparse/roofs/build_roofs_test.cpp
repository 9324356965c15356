// Roofs: every roof:shape on a rectangle, an L, a courtyard and a concave footprint
// (tests/data/roofs.osm), checked for what a roof must be whatever its shape.
#include <gtest/gtest.h>

#include <cmath>

#include "osmparse/pipeline.h"
#include "osmparse/roofs/build_roofs.h"
#include "osmparse/roofs/roof_geometry.h"
#include "tests/osmparse/parse_quietly.h"
#include "tests/test_support.h"

using namespace citygen;
using citygen::test::parse_quietly;
using citygen::test::source_path;

namespace {

const Scene& roofs_scene(ParseReport* report_out = nullptr) {
    static ParseReport report;
    static const Scene scene = [] {
        return parse_quietly(source_path("tests/data/roofs.osm"), report);
    }();
    if (report_out) *report_out = report;
    return scene;
}

Vec3 face_normal(const std::vector<Vec3>& p) {
    Vec3 n{0, 0, 0};
    for (size_t i = 0; i < p.size(); ++i) n = n + cross(p[i], p[(i + 1) % p.size()]);
    return normalize(n);
}

double projected_signed_area(const RoofFace& f) {
    Ring r;
    for (Vec3 p : f.points) r.push_back({p.x, p.y});
    return signed_area(r);
}

double net_area(const Building& b) {
    double a = std::fabs(signed_area(b.outer));
    for (const Ring& h : b.holes) a -= std::fabs(signed_area(h));
    return a;
}

bool over_footprint(Vec2 q, const Building& b, double tol) {
    if (!point_in_ring(q, b.outer) && distance_to_boundary(q, b.outer) > tol) return false;
    for (const Ring& h : b.holes)
        if (point_in_ring(q, h) && distance_to_boundary(q, h) > tol) return false;
    return true;
}

}  // namespace

TEST(Roofs, EveryFaceIsPlanarUnderTheTopAndOverTheFootprint) {
    const Scene& scene = roofs_scene();
    int with_faces = 0;
    for (const Building& b : scene.buildings) {
        if (b.roof_faces.empty()) continue;
        ++with_faces;
        EXPECT_GT(b.roof_height, 0.0) << to_string(b.osm);
        for (const RoofFace& f : b.roof_faces) {
            ASSERT_GE(f.points.size(), 3u);
            const Vec3 n = face_normal(f.points);
            ASSERT_NEAR(length(n), 1.0, 1e-9) << to_string(b.osm) << ": face without area";
            for (Vec3 p : f.points) {
                EXPECT_NEAR(dot(n, p - f.points[0]), 0.0, 2e-3) << to_string(b.osm) << " not planar";
                EXPECT_LE(p.z, b.height + 1e-3) << to_string(b.osm);
                EXPECT_GE(p.z, b.eaves_height() - 1e-3) << to_string(b.osm);
                EXPECT_TRUE(over_footprint({p.x, p.y}, b, 2e-3)) << to_string(b.osm) << " outside the footprint";
            }
            if (f.kind == RoofFaceKind::Gable) {
                EXPECT_NEAR(n.z, 0.0, 1e-6) << "gable walls stand upright";
            }
        }
    }
    EXPECT_GE(with_faces, 40);
}

TEST(Roofs, RoofFacesCoverTheFootprintOnce) {
    // Projected on the ground, the roof faces tile the footprint: their signed areas add up to
    // it (an onion's overhang counts negative where it faces down), so no gap and no overlap
    // can let light through between roof and walls.
    for (const Building& b : roofs_scene().buildings) {
        if (b.roof_faces.empty()) continue;
        double sum = 0;
        for (const RoofFace& f : b.roof_faces)
            if (f.kind == RoofFaceKind::Roof) sum += projected_signed_area(f);
        EXPECT_NEAR(sum, net_area(b), 1e-3 * net_area(b)) << to_string(b.osm) << " " << to_string(b.roof_shape);
    }
}

TEST(Roofs, GabledRectangleHasTwoSlopesAndTwoGableWalls) {
    for (const Building& b : roofs_scene().buildings) {
        if (b.roof_shape != RoofShape::Gabled || b.outer.size() != 4 || b.roof_inferred) continue;
        int roof = 0, gable = 0;
        double top = 0;
        for (const RoofFace& f : b.roof_faces) {
            (f.kind == RoofFaceKind::Roof ? roof : gable)++;
            for (Vec3 p : f.points) top = std::max(top, p.z);
        }
        EXPECT_EQ(roof, 2) << to_string(b.osm);
        EXPECT_EQ(gable, 2) << to_string(b.osm);
        EXPECT_NEAR(top, b.height, 1e-3);
        // The walls under the gables reach the ridge: a gable's top is the roof's top.
        for (const RoofFace& f : b.roof_faces)
            if (f.kind == RoofFaceKind::Gable) {
                double gable_top = 0;
                for (Vec3 p : f.points) gable_top = std::max(gable_top, p.z);
                EXPECT_NEAR(gable_top, b.height, 1e-3);
            }
    }
}

TEST(Roofs, ShapesThatNeedAConvexFootprintFallBackToHipped) {
    ParseReport report;
    const Scene& scene = roofs_scene(&report);
    int hipped_courtyards = 0;
    for (const Building& b : scene.buildings)
        if (!b.holes.empty() && !b.roof_faces.empty()) hipped_courtyards += b.roof_shape == RoofShape::Hipped;
    EXPECT_EQ(hipped_courtyards, 10);  // every shape but flat, on the courtyard
    // Gabled on the L and the U: the skeleton's end triangles folded into gable walls.
    EXPECT_EQ(report.note_count(ReportKind::Roofs, ReportReason::RoofGabledBuiltHipped), 1);
    int folded = 0;
    for (const Building& b : scene.buildings) {
        if (b.roof_shape != RoofShape::Gabled || b.outer.size() <= 4) continue;
        int gables = 0;
        for (const RoofFace& f : b.roof_faces) gables += f.kind == RoofFaceKind::Gable;
        EXPECT_EQ(gables, 2) << to_string(b.osm);  // the two ends of the L, of the U
        ++folded;
    }
    EXPECT_EQ(folded, 2);
}

TEST(Roofs, BadTagsFallBackAndAreCounted) {
    ParseReport report;
    const Scene& scene = roofs_scene(&report);
    EXPECT_EQ(report.note_count(ReportKind::Roofs, ReportReason::RoofHeightClamped), 1);
    EXPECT_EQ(report.note_count(ReportKind::Roofs, ReportReason::BadRoofAngle), 1);
    EXPECT_EQ(report.note_count(ReportKind::Roofs, ReportReason::UnknownRoofShape), 1);
    for (const Building& b : scene.buildings) EXPECT_LE(b.roof_height, b.height - b.min_height + 1e-9);
}

TEST(Roofs, RoofLevelsSitOnTopOfTheTaggedStoreys) {
    for (const Building& b : roofs_scene().buildings)
        if (b.height_source == HeightSource::Levels) {
            EXPECT_NEAR(b.eaves_height(), 6.0, 1e-9);  // building:levels=2
            EXPECT_NEAR(b.roof_height, 3.0, 1e-9);     // roof:levels=1
            EXPECT_EQ(b.roof_shape, RoofShape::Gabled);
        }
}

TEST(Roofs, DegenerateFootprintGivesNoRoof) {
    RoofSpec spec;
    spec.shape = RoofShape::Hipped;
    spec.eaves_z = 3;
    spec.height = 2;
    std::vector<RoofFace> faces;
    RoofShape built;
    ReportReason why{};
    const Ring sliver{{0, 0}, {10, 0}, {10, 0.01}, {0, 0.01}};
    EXPECT_FALSE(make_roof_faces(sliver, {}, spec, &faces, &built, &why));
    EXPECT_EQ(why, ReportReason::RoofDegenerateFootprint) << text_of(why);
    const Ring line{{0, 0}, {10, 0}, {20, 0}};
    why = ReportReason{};
    EXPECT_FALSE(make_roof_faces(line, {}, spec, &faces, &built, &why));
    EXPECT_EQ(why, ReportReason::RoofDegenerateFootprint) << text_of(why);
}

// The notes that name a shape say its roof:shape value (to_string), as the report always printed.
TEST(Roofs, ShapeNotesNameTheirShape) {
    for (int i = 0; i < kRoofShapeCount; ++i) {
        const RoofShape shape = static_cast<RoofShape>(i);
        const std::string name = to_string(shape);
        const RoofShapeNotes& notes = roof_shape_notes(shape);
        EXPECT_EQ(text_of(notes.tagged), name + " (tagged)");
        EXPECT_EQ(text_of(notes.by_default), name + " (default)");
        ASSERT_EQ(notes.failed_checks.has_value(), shape != RoofShape::Flat) << name;
        if (notes.failed_checks) {
            EXPECT_EQ(text_of(*notes.failed_checks), "faces failed the checks (" + name + "): flat");
        }
        ASSERT_EQ(notes.built_hipped.has_value(), shape != RoofShape::Flat && shape != RoofShape::Hipped) << name;
        if (notes.built_hipped) {
            EXPECT_EQ(text_of(*notes.built_hipped), name + " on a bent or holed footprint: built hipped");
        }
    }
}

TEST(Roofs, SkillionFacesItsDirection) {
    RoofSpec spec;
    spec.shape = RoofShape::Skillion;
    spec.eaves_z = 3;
    spec.height = 2;
    spec.has_direction = true;
    spec.direction = {0, -1};  // faces south: the north side is high
    std::vector<RoofFace> faces;
    RoofShape built;
    ReportReason why{};
    ASSERT_TRUE(make_roof_faces({{0, 0}, {10, 0}, {10, 6}, {0, 6}}, {}, spec, &faces, &built, &why));
    ASSERT_EQ(faces.size(), 1u);
    for (Vec3 p : faces[0].points) EXPECT_NEAR(p.z, p.y > 3 ? 5.0 : 3.0, 1e-9);
}

TEST(Roofs, DefaultsByTypeAreSeededAndDocumented) {
    Building house;
    house.type = "house";
    house.height = 8;
    double pitch = 0;
    int pitched = 0;
    RoofEvidence gabled_houses;  // a region whose tagged houses are gabled
    gabled_houses.tagged[static_cast<int>(RoofGroup::Houses)] = 200;
    gabled_houses.pitched[static_cast<int>(RoofGroup::Houses)] = 200;
    for (int id = 1; id <= 100; ++id) {
        house.osm.id = id;
        pitched += default_roof(house, 100, 1, &pitch, gabled_houses) != RoofShape::Flat;
        EXPECT_GE(pitch, 25);
        EXPECT_LE(pitch, 45);
    }
    EXPECT_GE(pitched, 97);
    Building shop = house;
    shop.type = "commercial";
    EXPECT_EQ(default_roof(shop, 100, 1, &pitch), RoofShape::Flat);
    Building block = house;
    block.type = "yes";
    block.height = 30;
    EXPECT_EQ(default_roof(block, 100, 1, &pitch), RoofShape::Flat);
    house.osm.id = 7;
    EXPECT_EQ(default_roof(house, 100, 1, &pitch), default_roof(house, 100, 1, &pitch));
}

// Hand-made buildings of one type and their OSM tags (roof:shape on the first `tagged`).
struct RoofTown {
    std::vector<Building> buildings;
    OsmData osm;
};
RoofTown roof_town(const std::string& type, int count, int tagged, const char* shape) {
    RoofTown t;
    for (int i = 0; i < count; ++i) {
        Building b;
        b.osm = {OsmType::Way, 1000 + i};
        const double x = 20.0 * i;
        b.outer = {{x, 0}, {x + 10, 0}, {x + 10, 8}, {x, 8}};
        b.type = type;
        b.height = 7;
        b.height_source = HeightSource::Tagged;
        t.buildings.push_back(b);
        OsmArea area;
        area.ref = b.osm;
        area.tags.entries.push_back({"building", type});
        if (i < tagged) area.tags.entries.push_back({"roof:shape", shape});
        t.osm.building_areas.push_back(area);
    }
    return t;
}
int pitched_untagged(const std::vector<Building>& v) {
    int n = 0;
    for (const Building& b : v) n += b.roof_inferred && b.roof_shape != RoofShape::Flat;
    return n;
}

TEST(Roofs, AnExtractWhoseTaggedRoofsAreFlatGetsFlatDefaults) {
    // Malta: flat roofs, and where a few are tagged, flat is what they say.
    RoofTown town = roof_town("house", 60, 20, "flat");
    ParseReport report;
    build_roofs(town.buildings, BuildingTagIndex(town.osm), BuildingParams{}, report);
    EXPECT_EQ(pitched_untagged(town.buildings), 0);
}

TEST(Roofs, AnExtractWhoseTaggedHousesArePitchedGetsPitchedHouses) {
    RoofTown town = roof_town("house", 60, 20, "gabled");
    ParseReport report;
    build_roofs(town.buildings, BuildingTagIndex(town.osm), BuildingParams{}, report);
    EXPECT_GE(pitched_untagged(town.buildings), 30) << "of 40 untagged houses";
    // Small untyped buildings in that region: the houses' tags say pitched there too.
    RoofTown yes = roof_town("yes", 60, 0, "");
    for (int i = 0; i < 20; ++i) yes.osm.building_areas[i] = town.osm.building_areas[i], yes.buildings[i] = town.buildings[i];
    build_roofs(yes.buildings, BuildingTagIndex(yes.osm), BuildingParams{}, report);
    EXPECT_GE(pitched_untagged(yes.buildings), 20) << "of 40 untagged small buildings";
}

TEST(Roofs, WithoutTaggedRoofsHomesAreFlatAndChurchesPitched) {
    // No evidence: the OSM default (flat) for homes and sheds, whatever the region; churches
    // and barns stay pitched.
    for (const char* type : {"house", "yes", "apartments", "garage"}) {
        RoofTown town = roof_town(type, 40, 0, "");
        ParseReport report;
        build_roofs(town.buildings, BuildingTagIndex(town.osm), BuildingParams{}, report);
        EXPECT_EQ(pitched_untagged(town.buildings), 0) << type;
    }
    RoofTown churches = roof_town("church", 10, 0, "");
    ParseReport report;
    build_roofs(churches.buildings, BuildingTagIndex(churches.osm), BuildingParams{}, report);
    EXPECT_EQ(pitched_untagged(churches.buildings), 10);
}

TEST(Roofs, CompassDirections) {
    double d = -1;
    EXPECT_TRUE(parse_compass_direction("SW", &d));
    EXPECT_DOUBLE_EQ(d, 225);
    EXPECT_TRUE(parse_compass_direction("-90", &d));
    EXPECT_DOUBLE_EQ(d, 270);
    EXPECT_FALSE(parse_compass_direction("up", &d));
    RoofShape s;
    EXPECT_TRUE(parse_roof_shape("half-hipped", &s));
    EXPECT_EQ(s, RoofShape::HalfHipped);
    EXPECT_FALSE(parse_roof_shape("pancake", &s));
}

TEST(Roofs, RidgeRoofsOnANotchedNearRectangle) {
    // Not convex (a notch in the long side and one at a corner) but nearly filling its
    // rectangle: every ridge shape is built as tagged, its faces tiling the footprint even where
    // a slope's clip falls apart into several pieces.
    const Ring notched{{0, 0}, {6, 0}, {6, 1}, {8, 1}, {8, 0}, {14, 0}, {14, 8}, {1, 8}, {1, 7}, {0, 7}};
    // A narrow slot from the north side to beyond the ridge: the north slope falls apart in two.
    const Ring slotted{{0, 0}, {20, 0}, {20, 8}, {10, 8}, {10, 2}, {9.5, 2}, {9.5, 8}, {0, 8}};
    for (const Ring& ring : {notched, slotted})
    for (RoofShape shape : {RoofShape::Gabled, RoofShape::HalfHipped, RoofShape::Gambrel, RoofShape::Mansard,
                            RoofShape::Round}) {
        RoofSpec spec;
        spec.shape = shape;
        spec.eaves_z = 6;
        spec.height = 3;
        std::vector<RoofFace> faces;
        RoofShape built;
        ReportReason why{};
        ASSERT_TRUE(make_roof_faces(ring, {}, spec, &faces, &built, &why)) << text_of(why);
        EXPECT_EQ(built, shape) << to_string(shape);
        double sum = 0;
        for (const RoofFace& f : faces) {
            sum += projected_signed_area(f);
            for (Vec3 p : f.points) {
                EXPECT_TRUE(point_in_ring({p.x, p.y}, ring) || distance_to_boundary({p.x, p.y}, ring) < 1e-6);
                EXPECT_LE(p.z, 9 + 1e-9);
                EXPECT_GE(p.z, 6 - 1e-9);
            }
        }
        EXPECT_NEAR(sum, signed_area(ring), 1e-6) << to_string(shape);
    }
}
