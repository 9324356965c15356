// Reading DEMs into the scene's grid, with fixtures written here with GDAL: a plane slope in the
// scene's own projection and in UTM 32N, feet, several DEMs, voids, partial and no overlap, and
// files GDAL cannot read. The only test that includes GDAL (to write its fixtures).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <functional>

#include <gdal.h>
#include <gdal_utils.h>
#include <ogr_srs_api.h>

#include "common/error.h"
#include "osmparse/terrain/build_terrain.h"
#include "osmparse/terrain/read_dem.h"
#include "tests/test_support.h"

using namespace citygen;
using citygen::test::TempDir;

namespace {

const Projection kScene(49.0, 8.0);  // Kaiserslautern's neighbourhood, in UTM zone 32N
const char* kSceneSrs = "+proj=tmerc +lat_0=49 +lon_0=8 +k=1 +x_0=0 +y_0=0 +datum=WGS84 +units=m +no_defs";

Box2 scene_bounds() {
    Box2 b;
    b.extend({-500, -400});
    b.extend({600, 500});
    return b;
}

// The slope every fixture holds, in the scene's metres.
double plane(double x, double y) { return 300 + 0.05 * x - 0.08 * y; }

struct Raster {
    Raster(std::string srs, double west, double north, double pixel, int width, int height,
           std::function<double(double, double)> value)
        : srs(std::move(srs)), west(west), north(north), pixel(pixel), width(width), height(height), value(std::move(value)) {}
    std::string srs;          // anything OSRSetFromUserInput takes
    double west, north, pixel;
    int width, height;
    std::function<double(double, double)> value;  // of a pixel centre, in the raster's CRS
    std::string unit;         // the band's unit type, "" for none
    bool has_nodata = false;
    double nodata = -9999;
};

void write_geotiff(const std::string& path, const Raster& r) {
    GDALAllRegister();
    GDALDatasetH ds = GDALCreate(GDALGetDriverByName("GTiff"), path.c_str(), r.width, r.height, 1, GDT_Float32, nullptr);
    ASSERT_NE(ds, nullptr);
    double gt[6] = {r.west, r.pixel, 0, r.north, 0, -r.pixel};
    GDALSetGeoTransform(ds, gt);
    OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
    ASSERT_EQ(OSRSetFromUserInput(srs, r.srs.c_str()), OGRERR_NONE) << r.srs;
    GDALSetSpatialRef(ds, srs);
    OSRDestroySpatialReference(srs);
    GDALRasterBandH band = GDALGetRasterBand(ds, 1);
    if (!r.unit.empty()) GDALSetRasterUnitType(band, r.unit.c_str());
    if (r.has_nodata) GDALSetRasterNoDataValue(band, r.nodata);
    std::vector<float> row(r.width);
    for (int line = 0; line < r.height; ++line) {
        for (int c = 0; c < r.width; ++c)
            row[c] = static_cast<float>(r.value(r.west + (c + 0.5) * r.pixel, r.north - (line + 0.5) * r.pixel));
        ASSERT_EQ(GDALRasterIO(band, GF_Write, 0, line, r.width, 1, row.data(), r.width, 1, GDT_Float32, 0, 0), CE_None);
    }
    GDALClose(ds);
}

// A raster in the scene's own projection over -1000..1000 m, 10 m pixels.
Raster scene_raster(std::function<double(double, double)> value) {
    return {kSceneSrs, -1000, 1000, 10, 200, 200, std::move(value)};
}

DemRead read(const std::vector<std::string>& paths, double cell = 0) {
    return read_dem({paths, scene_bounds(), cell}, kScene);
}

// The largest distance of the grid's covered nodes from the plane.
double largest_plane_error(const DemGrid& g) {
    double worst = 0;
    for (uint32_t j = 0; j < g.ny; ++j)
        for (uint32_t i = 0; i < g.nx; ++i) {
            const size_t k = g.index(i, j);
            EXPECT_TRUE(g.covered[k]);
            worst = std::fmax(worst, std::fabs(g.heights[k] - plane(g.origin.x + i * g.cell, g.origin.y + j * g.cell)));
        }
    return worst;
}

// UTM 32N -> the scene's metres through WGS84 and the scene's own projection (GeographicLib), so
// the fixture does not take GDAL's word for the scene's projection.
Vec2 utm_to_scene(double easting, double northing) {
    static OGRCoordinateTransformationH to_wgs84 = [] {
        OGRSpatialReferenceH utm = OSRNewSpatialReference(nullptr), wgs84 = OSRNewSpatialReference(nullptr);
        OSRImportFromEPSG(utm, 32632);
        OSRImportFromEPSG(wgs84, 4326);
        OSRSetAxisMappingStrategy(wgs84, OAMS_TRADITIONAL_GIS_ORDER);
        OGRCoordinateTransformationH ct = OCTNewCoordinateTransformation(utm, wgs84);
        OSRDestroySpatialReference(utm);
        OSRDestroySpatialReference(wgs84);
        return ct;
    }();
    double x = easting, y = northing;
    EXPECT_TRUE(OCTTransform(to_wgs84, 1, &x, &y, nullptr));
    return kScene.to_local(y, x);
}

std::string one_line_error(const std::function<void()>& f) {
    try {
        f();
    } catch (const Error& e) {
        const std::string m = e.what();
        EXPECT_EQ(m.find('\n'), std::string::npos) << m;
        return m;
    }
    ADD_FAILURE() << "no error";
    return "";
}

}  // namespace

TEST(ReadDem, PlaneInTheScenesProjectionIsThePlaneWithinACentimetre) {
    TempDir dir;
    write_geotiff(dir.file("plane.tif"), scene_raster(plane));
    const DemRead dem = read({dir.file("plane.tif")});
    EXPECT_EQ(dem.grid.cell, kRoadFitCell);  // finer than the DEM's own 10 m, for the roads
    EXPECT_LE(dem.grid.origin.x, -500 - kDemMarginCells * kRoadFitCell + 1e-9);
    EXPECT_GE(dem.grid.origin.x + (dem.grid.nx - 1) * dem.grid.cell, 600 + kDemMarginCells * kRoadFitCell - 1e-9);
    EXPECT_EQ(dem.grid.size(), 372u * 306u);  // 1113 x 915 m
    EXPECT_LT(largest_plane_error(dem.grid), 0.01);
    EXPECT_EQ(dem.vertical_datum, kAssumedVerticalDatum);
    // At the DEM's own resolution.
    const DemRead native = read({dir.file("plane.tif")}, 10);
    EXPECT_EQ(native.grid.size(), 115u * 95u);  // -520..620 x -420..520 m
    EXPECT_LT(largest_plane_error(native.grid), 0.01);
    // Between the DEM's pixels too.
    EXPECT_LT(largest_plane_error(read({dir.file("plane.tif")}, 7).grid), 0.01);
}

// The scene's origin in UTM 32N.
Vec2 origin_in_utm() {
    OGRSpatialReferenceH utm = OSRNewSpatialReference(nullptr), wgs84 = OSRNewSpatialReference(nullptr);
    OSRImportFromEPSG(utm, 32632);
    OSRImportFromEPSG(wgs84, 4326);
    OSRSetAxisMappingStrategy(wgs84, OAMS_TRADITIONAL_GIS_ORDER);
    OGRCoordinateTransformationH ct = OCTNewCoordinateTransformation(wgs84, utm);
    double x = kScene.origin_lon(), y = kScene.origin_lat();
    EXPECT_TRUE(OCTTransform(ct, 1, &x, &y, nullptr));
    OCTDestroyCoordinateTransformation(ct);
    OSRDestroySpatialReference(utm);
    OSRDestroySpatialReference(wgs84);
    return {x, y};
}

TEST(ReadDem, PlaneInUtm32NIsThePlaneWithinAFewCentimetres) {
    // The raster covers the bounds with 500 m to spare whatever the grids' angle (about 1.5 degrees).
    TempDir dir;
    const Vec2 o = origin_in_utm();
    Raster utm{"EPSG:32632", std::round(o.x) - 1200, std::round(o.y) + 1200, 10, 240, 240, [](double e, double n) {
                   const Vec2 p = utm_to_scene(e, n);
                   return plane(p.x, p.y);
               }};
    write_geotiff(dir.file("utm.tif"), utm);
    const DemRead dem = read({dir.file("utm.tif")}, 5);
    EXPECT_LT(largest_plane_error(dem.grid), 0.03);
}

// Two tiles side by side as one VRT mosaic: seamless, no node left out at the seam.
TEST(ReadDem, AVrtMosaicOfTilesIsOneDem) {
    TempDir dir;
    Raster west = scene_raster(plane), east = scene_raster(plane);
    west.width = east.width = 100;
    east.west = 0;
    write_geotiff(dir.file("west.tif"), west);
    write_geotiff(dir.file("east.tif"), east);
    const std::string tiles[] = {dir.file("west.tif"), dir.file("east.tif")};
    const char* names[] = {tiles[0].c_str(), tiles[1].c_str()};
    int usage_error = 0;
    GDALDatasetH vrt = GDALBuildVRT(dir.file("mosaic.vrt").c_str(), 2, nullptr, names, nullptr, &usage_error);
    ASSERT_NE(vrt, nullptr);
    GDALClose(vrt);
    EXPECT_LT(largest_plane_error(read({dir.file("mosaic.vrt")}, 5).grid), 0.01);
}

TEST(ReadDem, FeetAreConvertedAndNamed) {
    TempDir dir;
    Raster feet = scene_raster([](double x, double y) { return plane(x, y) / 0.3048; });
    feet.unit = "ft";
    write_geotiff(dir.file("feet.tif"), feet);
    const DemRead dem = read({dir.file("feet.tif")});
    EXPECT_LT(largest_plane_error(dem.grid), 0.01);
    EXPECT_EQ(dem.files_in_feet, 1u);
    feet.unit = "furlong";
    write_geotiff(dir.file("furlongs.tif"), feet);
    EXPECT_NE(one_line_error([&] { read({dir.file("furlongs.tif")}); }).find("a unit other than metres or feet ('furlong')"),
              std::string::npos);
}

TEST(ReadDem, TheVerticalDatumOfACompoundCrsIsNamed) {
    TempDir dir;
    const Vec2 o = origin_in_utm();
    Raster r{"EPSG:32632+5773", o.x - 1200, o.y + 1200, 10, 240, 240, [](double, double) { return 250.0; }};
    write_geotiff(dir.file("egm96.tif"), r);
    const DemRead dem = read({dir.file("egm96.tif")});
    EXPECT_EQ(dem.vertical_datum, "EGM96 height");
    EXPECT_EQ(dem.files_naming_datum, 1u);
}

// The first DEM given wins where both have a height; the second fills the first's voids.
TEST(ReadDem, WhereDemsOverlapTheFirstWithAHeightWins) {
    TempDir dir;
    Raster holed = scene_raster([](double x, double y) { return std::hypot(x, y) < 100 ? -9999 : 100; });
    holed.has_nodata = true;
    write_geotiff(dir.file("first.tif"), holed);
    write_geotiff(dir.file("second.tif"), scene_raster([](double, double) { return 200; }));
    const DemGrid g = read({dir.file("first.tif"), dir.file("second.tif")}).grid;
    auto at = [&](double x, double y) {
        return g.heights[g.index(static_cast<uint32_t>(std::lround((x - g.origin.x) / g.cell)),
                                 static_cast<uint32_t>(std::lround((y - g.origin.y) / g.cell)))];
    };
    EXPECT_FLOAT_EQ(at(0, 0), 200);
    EXPECT_FLOAT_EQ(at(300, 300), 100);
    const DemGrid alone = read({dir.file("first.tif")}).grid;
    EXPECT_TRUE(std::isnan(alone.heights[alone.index(static_cast<uint32_t>(std::lround(-alone.origin.x / alone.cell)),
                                                     static_cast<uint32_t>(std::lround(-alone.origin.y / alone.cell)))]));
}

TEST(ReadDem, ADemThatDoesNotOverlapIsOneClearLine) {
    TempDir dir;
    const Vec2 o = origin_in_utm();
    Raster far{"EPSG:32632", o.x, o.y + 100000, 10, 100, 100, [](double, double) { return 10.0; }};  // 100 km north
    write_geotiff(dir.file("far.tif"), far);
    const std::string m = one_line_error([&] { read({dir.file("far.tif")}); });
    EXPECT_NE(m.find("does not overlap the extract"), std::string::npos) << m;
    EXPECT_NE(m.find("far.tif"), std::string::npos) << m;
    EXPECT_NE(m.find("lat 49."), std::string::npos) << m;  // the extract's place
}

TEST(ReadDem, TruncatedCorruptOrMissingFilesAreOneClearLine) {
    TempDir dir;
    write_geotiff(dir.file("whole.tif"), scene_raster(plane));
    const std::string whole = test::read_text(dir.file("whole.tif"));
    test::write_text(dir.file("truncated.tif"), whole.substr(0, whole.size() * 2 / 5));
    test::write_text(dir.file("noise.tif"), std::string(5000, '\x5a'));
    test::write_text(dir.file("empty.hgt"), "");
    for (const char* name : {"truncated.tif", "noise.tif", "empty.hgt", "missing.tif"}) {
        const std::string m = one_line_error([&] { read({dir.file(name)}); });
        EXPECT_NE(m.find(name), std::string::npos) << m;
    }
    for (const char* name : {"noise.tif", "empty.hgt", "missing.tif"})  // before any parse
        EXPECT_NE(one_line_error([&] { check_dem_files({dir.file(name)}); }).find(name), std::string::npos);
}

TEST(ReadDem, AGridOverTheLimitNamesAResolutionThatFits) {
    TempDir dir;
    write_geotiff(dir.file("plane.tif"), scene_raster(plane));
    const std::string m = one_line_error([&] { read({dir.file("plane.tif")}, 0.05); });
    EXPECT_NE(m.find("over the limit"), std::string::npos) << m;
    EXPECT_NE(m.find("--dem-resolution 0.13 or more"), std::string::npos) << m;
    EXPECT_FALSE(one_line_error([&] { read({dir.file("plane.tif")}, -1); }).empty());
}

TEST(ReadDem, CellsAreRoundedToTwoDigitsAndAtLeastAMetre) {
    EXPECT_EQ(rounded_dem_cell(81.37), 81);
    EXPECT_EQ(rounded_dem_cell(0.3), 1);
    EXPECT_NEAR(rounded_dem_cell(9.97), 10, 1e-12);
    EXPECT_NEAR(rounded_dem_cell(2.46), 2.5, 1e-12);
    EXPECT_EQ(rounded_dem_cell(1234), 1200);
}

// The whole stage on a DEM that covers the west part of the scene, with a void on land and a
// void in the sea: counted in the report, every node with a height.
TEST(BuildTerrain, PartialOverlapAndVoidsAreFilledAndCounted) {
    TempDir dir;
    Raster r{kSceneSrs, -1000, 1000, 10, 110, 200, [](double x, double y) {
                 if (std::hypot(x + 300, y - 200) < 40) return -9999.0;  // a void on the slope
                 if (y < -200) return std::hypot(x + 300, y + 300) < 40 ? -9999.0 : 0.0;  // the sea, a void in it
                 return plane(x, y);
             }};
    r.has_nodata = true;
    write_geotiff(dir.file("west.tif"), r);  // to x = 100 m
    SceneHeader header;
    header.bounds_min = {-500, -400};
    header.bounds_max = {600, 500};
    TerrainParams params;
    params.dem_files = {dir.file("west.tif")};
    ParseReport report;
    const HeightField f = build_terrain(header, kScene, {}, params, report);
    EXPECT_GT(report.note_count(ReportKind::TerrainNodes, ReportReason::TerrainVoidFilled), 20);
    EXPECT_GT(report.note_count(ReportKind::TerrainNodes, ReportReason::TerrainVoidAtCoast), 20);
    EXPECT_GT(report.note_count(ReportKind::TerrainNodes, ReportReason::TerrainOutsideEveryDem), 40 * 90);
    EXPECT_EQ(report.kept_count(ReportKind::DemFiles), 1);
    EXPECT_EQ(report.note_count(ReportKind::DemFiles, ReportReason::DemVerticalDatumAssumed), 1);
    EXPECT_EQ(f.reference_altitude, 0);  // the sea is in the scene
    EXPECT_NEAR(f.at(-300, 200), plane(-300, 200), 0.5);
    EXPECT_NEAR(f.at(-300, -300), 0, 1e-6);
    EXPECT_NEAR(f.at(400, 100), plane(100, 100), 1);  // beyond the DEM, its edge's height
    EXPECT_EQ(f.at(400, 100), f.at(600, 100));
    for (float h : f.heights) EXPECT_TRUE(std::isfinite(h));
}
