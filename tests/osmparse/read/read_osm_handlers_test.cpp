// The read stage's handlers, one job each: fed objects built in memory (with node locations
// already filled in, as NodeLocationsForWays leaves them) and areas from libosmium's assembler.
#include <gtest/gtest.h>

#include <vector>

#include <osmium/area/assembler.hpp>
#include <osmium/builder/attr.hpp>
#include <osmium/memory/buffer.hpp>
#include <osmium/visitor.hpp>

#include "osmparse/read/read_osm.h"
#include "osmparse/read/read_osm_handlers.h"

using namespace citygen;
using namespace osmium::builder::attr;

namespace {

// A node ref with a location; `missing` leaves the location undefined (a node the extract cut off).
osmium::NodeRef at(osmium::object_id_type id, double lon, double lat) { return {id, osmium::Location{lon, lat}}; }
osmium::NodeRef missing(osmium::object_id_type id) { return osmium::NodeRef{id}; }

class Objects {
public:
    template <typename... Handlers>
    void apply(Handlers&... handlers) {
        osmium::apply(buffer_, handlers...);
    }
    osmium::memory::Buffer& buffer() { return buffer_; }

    // The area libosmium assembles from the most recently added way (empty when it refuses).
    template <typename... Handlers>
    void apply_area_of_last_way(Handlers&... handlers) {
        const osmium::Way* last = nullptr;
        for (const osmium::Way& w : buffer_.select<osmium::Way>()) last = &w;
        ASSERT_NE(last, nullptr);
        osmium::memory::Buffer areas{1024, osmium::memory::Buffer::auto_grow::yes};
        osmium::area::Assembler::config_type config;
        osmium::area::Assembler assembler{config};
        assembler(*last, areas);
        osmium::apply(areas, handlers...);
    }

private:
    osmium::memory::Buffer buffer_{1024, osmium::memory::Buffer::auto_grow::yes};
};

}  // namespace

TEST(StreetLampHandler, KeepsLocatedLampsAndCountsTheOthers) {
    OsmData data;
    ParseReport report;
    StreetLampHandler lamps{data, report};
    Objects objects;
    osmium::builder::add_node(objects.buffer(), _id(1), _location(7.0, 49.0), _tag("highway", "street_lamp"));
    osmium::builder::add_node(objects.buffer(), _id(2), _tag("highway", "street_lamp"));  // no location
    osmium::builder::add_node(objects.buffer(), _id(3), _location(8.0, 50.0), _tag("highway", "crossing"));
    objects.apply(lamps);
    ASSERT_EQ(data.street_lamps.size(), 1u);
    EXPECT_EQ(data.street_lamps[0].id, 1);
    EXPECT_DOUBLE_EQ(data.street_lamps[0].location.lat, 49.0);
    EXPECT_EQ(report.read_count(ReportKind::TaggedStreetLamps), 2);
    EXPECT_EQ(report.dropped_count(ReportKind::TaggedStreetLamps, ReportReason::InvalidLocation), 1);
    // A lamp extends the data's bounds.
    EXPECT_DOUBLE_EQ(data.min.lon, 7.0);
    EXPECT_DOUBLE_EQ(data.max.lon, 7.0);
}

TEST(RoadMarkHandler, KeepsCrossingsAndSignalsOnly) {
    OsmData data;
    ParseReport report;
    RoadMarkHandler marks{data, report};
    Objects objects;
    osmium::builder::add_node(objects.buffer(), _id(1), _location(7.0, 49.0), _tag("highway", "crossing"));
    osmium::builder::add_node(objects.buffer(), _id(2), _location(7.0, 49.0), _tag("highway", "traffic_signals"));
    osmium::builder::add_node(objects.buffer(), _id(3), _location(7.0, 49.0), _tag("highway", "stop"));
    objects.apply(marks);
    ASSERT_EQ(data.road_marks.size(), 2u);
    EXPECT_EQ(data.road_marks[1].id, 2);
    EXPECT_EQ(report.read_count(ReportKind::RoadMarkNodes), 2);
    EXPECT_GT(data.min.lat, data.max.lat) << "road marks do not extend the bounds";
}

TEST(TreeHandler, KeepsTreeNodesAndTreeRows) {
    OsmData data;
    ParseReport report;
    TreeHandler trees{data, report};
    Objects objects;
    osmium::builder::add_node(objects.buffer(), _id(1), _location(7.0, 49.0), _tag("natural", "tree"));
    osmium::builder::add_node(objects.buffer(), _id(2), _tag("natural", "tree"));
    osmium::builder::add_way(objects.buffer(), _id(10), _tag("natural", "tree_row"),
                             _nodes({at(1, 7.0, 49.0), at(2, 7.001, 49.0)}));
    osmium::builder::add_way(objects.buffer(), _id(11), _tag("natural", "tree_row"), _nodes({missing(3), missing(4)}));
    objects.apply(trees);
    ASSERT_EQ(data.trees.size(), 1u);
    EXPECT_EQ(report.dropped_count(ReportKind::MappedTrees, ReportReason::InvalidLocation), 1);
    ASSERT_EQ(data.tree_rows.size(), 1u);
    EXPECT_EQ(data.tree_rows[0].id, 10);
    EXPECT_EQ(report.read_count(ReportKind::TreeRows), 2);
    EXPECT_EQ(report.dropped_count(ReportKind::TreeRows, ReportReason::NodesMissing), 1);
}

TEST(HighwayHandler, CutsAClippedWayIntoRunsOfPresentNodes) {
    OsmData data;
    ParseReport report;
    HighwayHandler highways{data, report};
    Objects objects;
    osmium::builder::add_way(objects.buffer(), _id(5), _tag("highway", "residential"),
                             _nodes({at(1, 7.0, 49.0), at(2, 7.001, 49.0), missing(3), at(4, 7.003, 49.0),
                                     at(5, 7.004, 49.001), missing(6), at(7, 7.006, 49.0)}));
    osmium::builder::add_way(objects.buffer(), _id(6), _tag("highway", "service"), _nodes({missing(8), missing(9)}));
    osmium::builder::add_way(objects.buffer(), _id(7), _tag("building", "yes"), _nodes({at(1, 7.0, 49.0), at(2, 7.001, 49.0)}));
    objects.apply(highways);
    // Two runs of at least two nodes; the lone node 7 is no run but still extends the bounds.
    ASSERT_EQ(data.highways.size(), 2u);
    EXPECT_EQ(data.highways[0].nodes, (std::vector<int64_t>{1, 2}));
    EXPECT_FALSE(data.highways[0].cut_before);
    EXPECT_TRUE(data.highways[0].cut_after);
    EXPECT_EQ(data.highways[1].nodes, (std::vector<int64_t>{4, 5}));
    EXPECT_TRUE(data.highways[1].cut_before);
    EXPECT_TRUE(data.highways[1].cut_after);
    EXPECT_EQ(data.highways[1].id, 5);
    EXPECT_DOUBLE_EQ(data.max.lon, 7.006);
    EXPECT_DOUBLE_EQ(data.max.lat, 49.001);
    EXPECT_EQ(report.read_count(ReportKind::HighwayWays), 2);
    EXPECT_EQ(report.note_count(ReportKind::HighwayWays, ReportReason::ClippedAtEdge), 1);
    EXPECT_EQ(report.dropped_count(ReportKind::HighwayWays, ReportReason::NodesMissing), 1);
}

TEST(CoastlineAndRailwayHandlers, KeepTheirWaysWithoutExtendingTheBounds) {
    OsmData data;
    ParseReport report;
    CoastlineHandler coastlines{data, report};
    RailwayHandler railways{data, report};
    Objects objects;
    osmium::builder::add_way(objects.buffer(), _id(1), _tag("natural", "coastline"),
                             _nodes({at(1, 7.0, 49.0), at(2, 7.1, 49.0)}));
    osmium::builder::add_way(objects.buffer(), _id(2), _tag("railway", "tram"), _nodes({at(1, 7.0, 49.0), at(2, 7.1, 49.0)}));
    osmium::builder::add_way(objects.buffer(), _id(3), _tag("railway", "abandoned"),
                             _nodes({at(1, 7.0, 49.0), at(2, 7.1, 49.0)}));
    objects.apply(coastlines, railways);
    ASSERT_EQ(data.coastlines.size(), 1u);
    ASSERT_EQ(data.railways.size(), 1u);
    EXPECT_EQ(data.railways[0].id, 2);
    EXPECT_EQ(report.read_count(ReportKind::RailwayWays), 1);
    EXPECT_GT(data.min.lat, data.max.lat) << "coastlines and railways do not extend the bounds";
}

TEST(BuildingAreaHandler, CountsBuildingWaysAndKeepsTheAssembledArea) {
    OsmData data;
    ParseReport report;
    BuildingAreaHandler buildings{data, report};
    Objects objects;
    osmium::builder::add_way(objects.buffer(), _id(1), _tag("building", "yes"),
                             _nodes({at(1, 7.0, 49.0), at(2, 7.001, 49.0)}));  // not closed
    osmium::builder::add_way(objects.buffer(), _id(2), _tag("building", "yes"),
                             _nodes({at(1, 7.0, 49.0), missing(2), at(3, 7.0, 49.001), at(1, 7.0, 49.0)}));
    osmium::builder::add_way(objects.buffer(), _id(3), _tag("building", "house"),
                             _nodes({at(1, 7.0, 49.0), at(2, 7.001, 49.0), at(3, 7.001, 49.001), at(4, 7.0, 49.001),
                                     at(1, 7.0, 49.0)}));
    objects.apply(buildings);
    EXPECT_EQ(report.read_count(ReportKind::BuildingWays), 3);
    EXPECT_EQ(report.dropped_count(ReportKind::BuildingWays, ReportReason::NotClosed), 1);
    EXPECT_EQ(report.dropped_count(ReportKind::BuildingWays, ReportReason::NodesMissing), 1);
    objects.apply_area_of_last_way(buildings);
    ASSERT_EQ(data.building_areas.size(), 1u);
    const OsmArea& area = data.building_areas[0];
    EXPECT_EQ(area.ref.type, OsmType::Way);
    EXPECT_EQ(area.ref.id, 3);
    EXPECT_TRUE(area.tags.has("building", "house"));
    ASSERT_EQ(area.polygons.size(), 1u);
    EXPECT_EQ(area.polygons[0].outer.size(), 5u);
    EXPECT_DOUBLE_EQ(data.max.lat, 49.001);
    EXPECT_EQ(report.note_count(ReportKind::BuildingAreas, ReportReason::OutlinePassedForRepair), 0);
}

TEST(BuildingAreaHandler, KeepsEveryTagButTheAddress) {
    OsmData data;
    ParseReport report;
    BuildingAreaHandler buildings{data, report};
    Objects objects;
    osmium::builder::add_way(objects.buffer(), _id(3), _tag("building", "house"), _tag("addr:street", "Marktstraße"),
                             _tag("addr:housenumber", "12"), _tag("roof:shape", "gabled"),
                             _nodes({at(1, 7.0, 49.0), at(2, 7.001, 49.0), at(3, 7.001, 49.001), at(4, 7.0, 49.001),
                                     at(1, 7.0, 49.0)}));
    objects.apply(buildings);
    objects.apply_area_of_last_way(buildings);
    ASSERT_EQ(data.building_areas.size(), 1u);
    const OsmTags& tags = data.building_areas[0].tags;
    EXPECT_EQ(tags.entries.size(), 2u);
    EXPECT_TRUE(tags.has("building", "house"));
    EXPECT_TRUE(tags.has("roof:shape", "gabled"));
    EXPECT_EQ(tags.get("addr:street"), nullptr);
}

TEST(BuildingAreaHandler, PassesARefusedSelfIntersectingOutlineOnForRepair) {
    OsmData data;
    ParseReport report;
    BuildingAreaHandler buildings{data, report};
    Objects objects;
    // A bow tie: libosmium refuses the ring; the way's own outline goes on instead.
    osmium::builder::add_way(objects.buffer(), _id(9), _tag("building", "yes"),
                             _nodes({at(1, 7.0, 49.0), at(2, 7.001, 49.001), at(3, 7.001, 49.0), at(4, 7.0, 49.001),
                                     at(1, 7.0, 49.0)}));
    objects.apply(buildings);
    objects.apply_area_of_last_way(buildings);
    ASSERT_EQ(data.building_areas.size(), 1u);
    ASSERT_EQ(data.building_areas[0].polygons.size(), 1u);
    EXPECT_EQ(data.building_areas[0].polygons[0].outer.size(), 5u);
    EXPECT_DOUBLE_EQ(data.building_areas[0].polygons[0].outer[1].lat, 49.001);
    EXPECT_EQ(report.note_count(ReportKind::BuildingAreas, ReportReason::OutlinePassedForRepair), 1);
}

TEST(LandCoverHandler, KeepsAreasWithALandCoverClassButNoBuildings) {
    OsmData data;
    ParseReport report;
    LandCoverHandler land_cover{data, report};
    BuildingAreaHandler buildings{data, report};
    Objects objects;
    auto square = [](int64_t first) {
        return std::vector<osmium::NodeRef>{at(first, 7.0, 49.0), at(first + 1, 7.001, 49.0),
                                                      at(first + 2, 7.001, 49.001), at(first + 3, 7.0, 49.001),
                                                      at(first, 7.0, 49.0)};
    };
    osmium::builder::add_way(objects.buffer(), _id(1), _tag("landuse", "forest"), _nodes(square(1)));
    objects.apply_area_of_last_way(land_cover, buildings);
    osmium::builder::add_way(objects.buffer(), _id(2), _tag("highway", "pedestrian"), _nodes(square(10)));
    objects.apply_area_of_last_way(land_cover, buildings);
    osmium::builder::add_way(objects.buffer(), _id(3), _tags({{"building", "yes"}, {"landuse", "forest"}}),
                             _nodes(square(20)));
    objects.apply(buildings);
    objects.apply_area_of_last_way(land_cover, buildings);
    ASSERT_EQ(data.land_cover_areas.size(), 1u);
    EXPECT_EQ(data.land_cover_areas[0].ref.id, 1);
    EXPECT_EQ(report.read_count(ReportKind::LandCoverAreas), 1);
    ASSERT_EQ(data.building_areas.size(), 1u);
    EXPECT_EQ(data.building_areas[0].ref.id, 3);
}

TEST(ReadOsm, AssemblesAMultipolygonWhoseRelationComesAfterItsWays) {
    // One walk over the file: the ways are kept aside until the relation (last in the file) is known.
    ParseReport report;
    const OsmData data = read_osm(std::string(CITYGEN_SOURCE_DIR) + "/tests/data/courtyard_multipolygon.osm", true, report);
    int relations = 0;
    for (const OsmArea& a : data.building_areas) {
        if (a.ref.type != OsmType::Relation) continue;
        ++relations;
        ASSERT_EQ(a.polygons.size(), 1u);
        EXPECT_EQ(a.polygons[0].inners.size(), 1u);
    }
    EXPECT_EQ(relations, 1);
    EXPECT_EQ(report.read_count(ReportKind::BuildingRelations), 1);
}

TEST(RetainingWallHandler, KeepsOpenAndClosedWallsWithTheirHeightAndMaterialOnly) {
    OsmData data;
    ParseReport report;
    RetainingWallHandler walls{data, report};
    Objects objects;
    osmium::builder::add_way(objects.buffer(), _id(20), _tag("barrier", "retaining_wall"), _tag("height", "4"),
                             _tag("material", "stone"), _tag("name", "Mur"),
                             _nodes({at(1, 7.0, 49.0), at(2, 7.001, 49.0)}));
    osmium::builder::add_way(objects.buffer(), _id(21), _tag("barrier", "retaining_wall"),
                             _nodes({at(3, 7.0, 49.0), at(4, 7.001, 49.0), at(5, 7.001, 49.001), at(3, 7.0, 49.0)}));
    osmium::builder::add_way(objects.buffer(), _id(22), _tag("barrier", "retaining_wall"), _nodes({missing(6), missing(7)}));
    osmium::builder::add_way(objects.buffer(), _id(23), _tag("barrier", "wall"), _nodes({at(1, 7.0, 49.0), at(2, 7.001, 49.0)}));
    objects.apply(walls);
    ASSERT_EQ(data.retaining_walls.size(), 3u);
    EXPECT_EQ(data.retaining_walls[0].id, 20);
    EXPECT_STREQ(data.retaining_walls[0].tags.get("height"), "4");
    EXPECT_STREQ(data.retaining_walls[0].tags.get("material"), "stone");
    EXPECT_EQ(data.retaining_walls[0].tags.get("name"), nullptr) << "only the tags that are read";
    EXPECT_EQ(data.retaining_walls[1].locations.size(), 4u) << "a closed way, its first node repeated";
    EXPECT_TRUE(data.retaining_walls[2].locations.empty()) << "no node present: an empty run, counted later";
    EXPECT_EQ(report.read_count(ReportKind::RetainingWalls), 0) << "counted only when kept (with a field)";
    EXPECT_GT(data.min.lat, data.max.lat) << "walls do not extend the bounds";
}
