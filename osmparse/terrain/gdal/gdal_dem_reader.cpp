// The only translation unit that includes GDAL: the module osmparse loads for --dem
// (gdal_dem_reader.h).
#include "osmparse/terrain/gdal/gdal_dem_reader.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <cpl_vsi.h>
#include <gdal.h>
#include <gdal_alg.h>
#include <gdalwarper.h>
#include <ogr_srs_api.h>

#include "common/error.h"
#include "common/scene_limits.h"

namespace citygen {

namespace {

// GDAL's messages go to its last-error slot instead of stderr while one of these lives, so a
// failure becomes our one line.
class QuietGdal {
public:
    QuietGdal() {
        static std::once_flag registered;
        std::call_once(registered, [] {
            GDALAllRegister();
            // A GeoTIFF's vertical CRS (its datum and units) is reported only when asked for.
            CPLSetConfigOption("GTIFF_REPORT_COMPD_CS", "YES");
        });
        CPLPushErrorHandler(CPLQuietErrorHandler);
        CPLErrorReset();
    }
    ~QuietGdal() { CPLPopErrorHandler(); }
    QuietGdal(const QuietGdal&) = delete;
    QuietGdal& operator=(const QuietGdal&) = delete;
};

// GDAL's last error on one line, or `fallback`.
std::string gdal_message(const char* fallback) {
    std::string m = CPLGetLastErrorMsg();
    if (m.empty()) return fallback;
    std::replace(m.begin(), m.end(), '\n', ' ');
    return m;
}

struct CloseDataset {
    void operator()(void* ds) const { GDALClose(ds); }
};
using Dataset = std::unique_ptr<void, CloseDataset>;

struct DestroyTransformer {
    void operator()(void* t) const { GDALDestroyGenImgProjTransformer(t); }
};
using Transformer = std::unique_ptr<void, DestroyTransformer>;

std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

bool ends_with(const std::string& s, const std::string& tail) {
    return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

// The raster inside a zip: the first file in it (by name) that GDAL opens.
Dataset open_in_zip(const std::string& path) {
    const std::string zip = "/vsizip/" + std::filesystem::absolute(path).string();
    char** entries = VSIReadDirRecursive(zip.c_str());
    std::vector<std::string> names;
    for (char** e = entries; e && *e; ++e)
        if (!ends_with(*e, "/")) names.emplace_back(*e);
    CSLDestroy(entries);
    if (names.empty()) throw Error("DEM " + path + ": not a zip file GDAL reads, or an empty one");
    std::sort(names.begin(), names.end());
    for (const std::string& name : names)
        if (GDALDatasetH ds = GDALOpenEx((zip + "/" + name).c_str(), GDAL_OF_RASTER | GDAL_OF_VERBOSE_ERROR, nullptr, nullptr, nullptr))
            return Dataset(ds);
    throw Error("DEM " + path + ": no raster GDAL reads inside the zip (" + gdal_message("no supported file") + ")");
}

// Opens a DEM and checks it can be placed: a raster band, georeferencing and a CRS.
Dataset open_dem(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::exists(path, ec)) throw Error("DEM " + path + ": no such file");
    if (!std::filesystem::is_regular_file(path, ec)) throw Error("DEM " + path + ": not a regular file");
    Dataset ds;
    if (ends_with(lower(path), ".zip")) ds = open_in_zip(path);
    else ds.reset(GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_VERBOSE_ERROR, nullptr, nullptr, nullptr));
    if (!ds) throw Error("DEM " + path + ": not a raster GDAL reads (" + gdal_message("unsupported format") + ")");
    double gt[6];
    if (GDALGetRasterCount(ds.get()) < 1) throw Error("DEM " + path + ": has no raster band");
    if (GDALGetGeoTransform(ds.get(), gt) != CE_None && GDALGetGCPCount(ds.get()) == 0)
        throw Error("DEM " + path + ": has no georeferencing (no geotransform or ground control points)");
    if (!GDALGetSpatialRef(ds.get()) && !GDALGetGCPSpatialRef(ds.get()))
        throw Error("DEM " + path + ": has no coordinate reference system");
    return ds;
}

// What turns a DEM's raw values into metres, and the vertical datum it names.
struct DemSource {
    std::string path;
    Dataset ds;
    double scale = 1, offset = 0;  // metres = raw * scale + offset (band scale, offset and unit)
    bool has_nodata = false;
    double nodata = 0;
    bool in_feet = false;   // converted to metres
    std::string datum;      // "" when it names none
    bool above_ellipsoid = false;
};

constexpr double kFoot = 0.3048, kUsSurveyFoot = 1200.0 / 3937.0;  // metres

// Metres per unit of a band's unit name (GDAL's and the usual spellings), 0 when unknown.
double metres_per_unit(const std::string& unit) {
    const std::string u = lower(unit);
    if (u.empty() || u == "m" || u == "metre" || u == "metres" || u == "meter" || u == "meters") return 1;
    if (u == "ft" || u == "foot" || u == "feet" || u == "international foot") return kFoot;
    if (u == "us-ft" || u == "ftus" || u == "us survey foot" || u == "us_survey_foot" || u == "foot_us") return kUsSurveyFoot;
    return 0;
}

// The vertical datum and units of a DEM: from a compound CRS's vertical part, else the band's unit.
void vertical_frame(DemSource& s, GDALRasterBandH band) {
    OGRSpatialReferenceH srs = GDALGetSpatialRef(s.ds.get());
    double unit = 1;
    std::string unit_name;
    if (srs && OSRIsCompound(srs)) {
        if (const char* name = OSRGetAttrValue(srs, "COMPD_CS|VERT_CS", 0)) s.datum = name;
        char* name = nullptr;
        unit = OSRGetTargetLinearUnits(srs, "VERT_CS", &name);
        if (name) unit_name = name;
        for (double known : {1.0, kFoot, kUsSurveyFoot})
            if (std::fabs(unit - known) < 1e-6) unit = known;
    } else {
        if (srs && OSRGetAxesCount(srs) == 3) {
            const char* datum = OSRGetAttrValue(srs, "DATUM", 0);
            s.datum = std::string("the ellipsoid of ") + (datum ? datum : "its datum") + " (not sea level)";
            s.above_ellipsoid = true;
        }
        const char* unit_type = GDALGetRasterUnitType(band);
        unit_name = unit_type ? unit_type : "";
        unit = metres_per_unit(unit_name);
    }
    if (unit != 1 && unit != kFoot && unit != kUsSurveyFoot)
        throw Error("DEM " + s.path + ": heights in a unit other than metres or feet ('" + unit_name + "')");
    s.in_feet = unit != 1;
    int has = 0;
    const double band_scale = GDALGetRasterScale(band, &has);
    const double band_offset = GDALGetRasterOffset(band, &has);
    s.scale = band_scale * unit;
    s.offset = band_offset * unit;
}

DemSource dem_source(const std::string& path) {
    DemSource s;
    s.path = path;
    s.ds = open_dem(path);
    GDALRasterBandH band = GDALGetRasterBand(s.ds.get(), 1);
    int has = 0;
    s.nodata = GDALGetRasterNoDataValue(band, &has);
    s.has_nodata = has != 0;
    vertical_frame(s, band);
    return s;
}

// The scene's transverse Mercator (common/projection.h) on its origin, as GDAL's WKT.
std::string scene_wkt(double origin_lat, double origin_lon) {
    char proj[256];
    std::snprintf(proj, sizeof proj, "+proj=tmerc +lat_0=%.12g +lon_0=%.12g +k=1 +x_0=0 +y_0=0 +datum=WGS84 +units=m +no_defs",
                  origin_lat, origin_lon);
    OGRSpatialReferenceH srs = OSRNewSpatialReference(nullptr);
    char* wkt = nullptr;
    if (OSRImportFromProj4(srs, proj) != OGRERR_NONE || OSRExportToWkt(srs, &wkt) != OGRERR_NONE) {
        OSRDestroySpatialReference(srs);
        throw Error(std::string("GDAL cannot make the scene's projection (") + gdal_message(proj) + ")");
    }
    std::string out = wkt;
    CPLFree(wkt);
    OSRDestroySpatialReference(srs);
    return out;
}

// A transformer between a DEM's pixels and the scene's metres (or, with a target dataset, its pixels).
Transformer make_transformer(const DemSource& s, GDALDatasetH target, const std::string& wkt) {
    const std::string dst_srs = "DST_SRS=" + wkt;
    const char* options[] = {dst_srs.c_str(), nullptr};
    void* exact = GDALCreateGenImgProjTransformer2(s.ds.get(), target, target ? nullptr : const_cast<char**>(options));
    if (!exact) throw Error("DEM " + s.path + ": cannot be placed in the scene's projection (" + gdal_message("no transform") + ")");
    // Exact, not GDAL's approximating transformer: its interpolation spans follow the grid's
    // extent, so a node's height would depend on the extract around it, and the farm's tiles
    // would not give one parse's terrain (docs/farm.md).
    return Transformer(exact);
}

// The DEM's own resolution in the scene's metres (GDAL's suggested output cell).
double native_cell(const DemSource& s, const std::string& wkt) {
    Transformer t = make_transformer(s, nullptr, wkt);
    double gt[6];
    int pixels = 0, lines = 0;
    if (GDALSuggestedWarpOutput(s.ds.get(), GDALGenImgProjTransform, t.get(), gt, &pixels, &lines) != CE_None)
        throw Error("DEM " + s.path + ": cannot be placed in the scene's projection (" + gdal_message("no extent") + ")");
    return std::fabs(gt[1]);
}

// The DEM's raster extent in WGS84, for the message when no DEM overlaps the extract.
DemExtent dem_extent(const DemSource& s) {
    DemExtent e;
    e.path = s.path;
    double gt[6];
    OGRSpatialReferenceH srs = GDALGetSpatialRef(s.ds.get());
    if (!srs || GDALGetGeoTransform(s.ds.get(), gt) != CE_None) return e;
    const double w = GDALGetRasterXSize(s.ds.get()), h = GDALGetRasterYSize(s.ds.get());
    const double xs[] = {gt[0], gt[0] + w * gt[1] + h * gt[2]}, ys[] = {gt[3], gt[3] + w * gt[4] + h * gt[5]};
    OGRSpatialReferenceH wgs84 = OSRNewSpatialReference(nullptr);
    OSRImportFromEPSG(wgs84, 4326);
    OSRSetAxisMappingStrategy(wgs84, OAMS_TRADITIONAL_GIS_ORDER);
    OGRSpatialReferenceH source = OSRClone(srs);
    OSRSetAxisMappingStrategy(source, OAMS_TRADITIONAL_GIS_ORDER);
    OGRCoordinateTransformationH ct = OCTNewCoordinateTransformation(source, wgs84);
    e.known = ct && OCTTransformBounds(ct, std::min(xs[0], xs[1]), std::min(ys[0], ys[1]), std::max(xs[0], xs[1]),
                                       std::max(ys[0], ys[1]), &e.lon0, &e.lat0, &e.lon1, &e.lat1, 21);
    if (ct) OCTDestroyCoordinateTransformation(ct);
    OSRDestroySpatialReference(source);
    OSRDestroySpatialReference(wgs84);
    return e;
}

// An in-memory raster of the grid's nodes, each node the centre of a pixel, rows north first.
Dataset target_dataset(const DemGrid& g, const std::string& wkt) {
    Dataset ds(GDALCreate(GDALGetDriverByName("MEM"), "", static_cast<int>(g.nx), static_cast<int>(g.ny), 1,
                          GDT_Float32, nullptr));
    if (!ds) throw Error("cannot allocate the DEM grid (" + gdal_message("out of memory") + ")");
    double gt[6] = {g.origin.x - g.cell / 2, g.cell, 0, g.origin.y + (g.ny - 1) * g.cell + g.cell / 2, 0, -g.cell};
    GDALSetGeoTransform(ds.get(), gt);
    GDALSetProjection(ds.get(), wkt.c_str());
    GDALSetRasterNoDataValue(GDALGetRasterBand(ds.get(), 1), NAN);
    return ds;
}

// Marks the nodes within the DEM's samples (between its outermost pixel centres, where bilinear
// resampling has all four neighbours; the half pixel beyond is its edge); returns how many.
size_t mark_coverage(const DemSource& s, void* transformer, const DemGrid& g, std::vector<uint8_t>& inside) {
    const double w = GDALGetRasterXSize(s.ds.get()), h = GDALGetRasterYSize(s.ds.get());
    std::vector<double> x(g.nx), y(g.nx), z(g.nx);
    std::vector<int> ok(g.nx);
    size_t count = 0;
    for (uint32_t line = 0; line < g.ny; ++line) {
        for (uint32_t i = 0; i < g.nx; ++i) x[i] = i + 0.5, y[i] = line + 0.5, z[i] = 0;
        GDALGenImgProjTransform(transformer, TRUE, static_cast<int>(g.nx), x.data(), y.data(), z.data(), ok.data());
        for (uint32_t i = 0; i < g.nx; ++i)
            if (ok[i] && x[i] >= 0.5 && x[i] <= w - 0.5 && y[i] >= 0.5 && y[i] <= h - 0.5) {
                inside[g.index(i, g.ny - 1 - line)] = 1;
                ++count;
            }
    }
    return count;
}

// Warps the DEM's first band into the target, bilinear; pixels without a source stay NaN.
void warp_into(const DemSource& s, void* transformer, GDALDatasetH target) {
    GDALWarpOptions* wo = GDALCreateWarpOptions();
    wo->hSrcDS = s.ds.get();
    wo->hDstDS = target;
    wo->nBandCount = 1;
    wo->panSrcBands = static_cast<int*>(CPLMalloc(sizeof(int)));
    wo->panDstBands = static_cast<int*>(CPLMalloc(sizeof(int)));
    wo->panSrcBands[0] = wo->panDstBands[0] = 1;
    wo->eResampleAlg = GRA_Bilinear;
    wo->eWorkingDataType = GDT_Float32;
    if (s.has_nodata) {
        wo->padfSrcNoDataReal = static_cast<double*>(CPLMalloc(sizeof(double)));
        wo->padfSrcNoDataReal[0] = s.nodata;
    }
    wo->padfDstNoDataReal = static_cast<double*>(CPLMalloc(sizeof(double)));
    wo->padfDstNoDataReal[0] = NAN;
    wo->papszWarpOptions = CSLSetNameValue(wo->papszWarpOptions, "INIT_DEST", "NO_DATA");
    wo->pfnTransformer = GDALGenImgProjTransform;
    wo->pTransformerArg = transformer;
    CPLErrorReset();
    GDALWarpOperationH op = GDALCreateWarpOperation(wo);
    CPLErr err = op ? GDALChunkAndWarpImage(op, 0, 0, GDALGetRasterXSize(target), GDALGetRasterYSize(target)) : CE_Failure;
    if (op) GDALDestroyWarpOperation(op);
    wo->pTransformerArg = nullptr;  // the caller's
    GDALDestroyWarpOptions(wo);
    if (err != CE_None || CPLGetLastErrorType() >= CE_Failure)
        throw Error("DEM " + s.path + ": cannot read its heights (" + gdal_message("read error") + ")");
}

// Takes the warped heights, in metres, of the nodes the DEM covers that no earlier DEM gave a height.
void take_heights(const DemSource& s, GDALDatasetH target, const std::vector<uint8_t>& inside, DemGrid& g) {
    GDALRasterBandH band = GDALGetRasterBand(target, 1);
    std::vector<float> row(g.nx);
    for (uint32_t line = 0; line < g.ny; ++line) {
        if (GDALRasterIO(band, GF_Read, 0, static_cast<int>(line), static_cast<int>(g.nx), 1, row.data(),
                         static_cast<int>(g.nx), 1, GDT_Float32, 0, 0) != CE_None)
            throw Error("DEM " + s.path + ": cannot read its heights (" + gdal_message("read error") + ")");
        for (uint32_t i = 0; i < g.nx; ++i) {
            const size_t k = g.index(i, g.ny - 1 - line);
            if (!inside[k]) continue;
            g.covered[k] = 1;
            if (std::isfinite(row[i]) && !altitude_within_limit(g.heights[k]))
                g.heights[k] = static_cast<float>(row[i] * s.scale + s.offset);
        }
    }
}

// Runs `f`, turning an error into its one line.
template <typename F>
void catching(std::string& error, F&& f) {
    try {
        QuietGdal quiet;
        f();
    } catch (const std::exception& e) {
        error = e.what();
    }
}

}  // namespace

}  // namespace citygen

using namespace citygen;

extern "C" void citygen_check_dem_files(const std::vector<std::string>& paths, std::string& error) {
    catching(error, [&] {
        for (const std::string& path : paths) dem_source(path);
    });
}

extern "C" void citygen_native_dem_cell(const std::vector<std::string>& paths, double origin_lat, double origin_lon,
                                        double& cell, std::string& error) {
    catching(error, [&] {
        const std::string wkt = scene_wkt(origin_lat, origin_lon);
        cell = INFINITY;
        for (const std::string& path : paths) cell = std::min(cell, native_cell(dem_source(path), wkt));
    });
}

extern "C" void citygen_warp_dems(const std::vector<std::string>& paths, double origin_lat, double origin_lon,
                                  DemRead& out, std::string& error) {
    catching(error, [&] {
        const std::string wkt = scene_wkt(origin_lat, origin_lon);
        Dataset target = target_dataset(out.grid, wkt);
        for (const std::string& path : paths) {
            const DemSource s = dem_source(path);
            Transformer transformer = make_transformer(s, target.get(), wkt);
            std::vector<uint8_t> inside(out.grid.size(), 0);
            if (mark_coverage(s, transformer.get(), out.grid, inside) == 0) {
                out.unused.push_back(dem_extent(s));
                continue;
            }
            warp_into(s, transformer.get(), target.get());
            take_heights(s, target.get(), inside, out.grid);
            ++out.files_used;
            out.files_in_feet += s.in_feet;
            out.files_above_ellipsoid += s.above_ellipsoid;
            out.files_naming_datum += !s.datum.empty() && !s.above_ellipsoid;
            if (out.vertical_datum.empty()) out.vertical_datum = s.datum;
        }
    });
}
