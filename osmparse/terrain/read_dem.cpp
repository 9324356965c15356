// The grid and the messages; GDAL's part through the module (gdal/gdal_dem_reader.h).
#include "osmparse/terrain/read_dem.h"

#include <dlfcn.h>

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "common/error.h"
#include "common/scene_limits.h"
#include "osmparse/terrain/gdal/gdal_dem_reader.h"

namespace citygen {

namespace {

// The module's entry points, loaded once from beside the running program.
struct DemModule {
    decltype(&citygen_check_dem_files) check_files = nullptr;
    decltype(&citygen_native_dem_cell) native_cell = nullptr;
    decltype(&citygen_warp_dems) warp = nullptr;
};

template <typename F>
F entry_point(void* module, const char* name, const std::string& path) {
    void* f = dlsym(module, name);
    if (!f) throw Error(path + ": no " + name + " (a module of another citygen version?)");
    return reinterpret_cast<F>(f);
}

const DemModule& dem_module() {
    static const DemModule module = [] {
        std::error_code ec;
        const std::filesystem::path program = std::filesystem::read_symlink("/proc/self/exe", ec);
        const std::string path = (program.parent_path() / CITYGEN_DEM_READER).string();
        void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
        if (!handle) throw Error(std::string("--dem needs GDAL's module beside the program: ") + dlerror());
        DemModule m;
        m.check_files = entry_point<decltype(m.check_files)>(handle, "citygen_check_dem_files", path);
        m.native_cell = entry_point<decltype(m.native_cell)>(handle, "citygen_native_dem_cell", path);
        m.warp = entry_point<decltype(m.warp)>(handle, "citygen_warp_dems", path);
        return m;
    }();
    return module;
}

// Calls a module entry point with `args` and an error string, and throws what it reports.
template <typename F, typename... Args>
void call(F f, Args&&... args) {
    std::string error;
    f(std::forward<Args>(args)..., error);
    if (!error.empty()) throw Error(error);
}

// Latitude and longitude ranges, for messages.
std::string degrees_box(double lat0, double lon0, double lat1, double lon1) {
    char text[128];
    std::snprintf(text, sizeof text, "lat %.4f..%.4f, lon %.4f..%.4f", lat0, lat1, lon0, lon1);
    return text;
}

std::string extract_extent(const Box2& b, const Projection& projection) {
    double lat0 = 90, lon0 = 180, lat1 = -90, lon1 = -180;
    for (Vec2 p : {b.min, b.max, Vec2(b.min.x, b.max.y), Vec2(b.max.x, b.min.y)}) {
        double lat = 0, lon = 0;
        projection.to_wgs84(p, lat, lon);
        lat0 = std::min(lat0, lat), lat1 = std::max(lat1, lat);
        lon0 = std::min(lon0, lon), lon1 = std::max(lon1, lon);
    }
    return degrees_box(lat0, lon0, lat1, lon1);
}

std::string no_overlap_message(const DemRead& read, const Box2& bounds, const Projection& projection) {
    std::string m = std::string(read.unused.size() == 1 ? "the DEM does not" : "none of the DEMs does") +
                    " overlap the extract (extract: " + extract_extent(bounds, projection);
    for (const DemExtent& e : read.unused)
        m += "; " + e.path + ": " + (e.known ? degrees_box(e.lat0, e.lon0, e.lat1, e.lon1) : "extent unknown");
    return m + ")";
}

// The smallest cell of two significant digits at least `metres`.
double rounded_up_cell(double metres) {
    const double unit = std::pow(10.0, std::floor(std::log10(metres)) - 1);
    return std::ceil(metres / unit) * unit;
}

// The grid's nodes over the bounds and kDemMarginCells beyond, on multiples of the cell.
DemGrid grid_over(const Box2& bounds, double cell) {
    if (!(cell > 0) || !std::isfinite(cell)) throw Error("the DEM resolution must be a positive number of metres");
    const double i0 = std::floor(bounds.min.x / cell) - kDemMarginCells, i1 = std::ceil(bounds.max.x / cell) + kDemMarginCells;
    const double j0 = std::floor(bounds.min.y / cell) - kDemMarginCells, j1 = std::ceil(bounds.max.y / cell) + kDemMarginCells;
    const double nx = i1 - i0 + 1, ny = j1 - j0 + 1;
    if (!(nx * ny <= static_cast<double>(kMaxHeightFieldNodes))) {
        char text[256];
        std::snprintf(text, sizeof text,
                      "a height field of %.0f x %.0f nodes at %g m is over the limit of %llu nodes: choose "
                      "--dem-resolution %g or more",
                      nx, ny, cell, static_cast<unsigned long long>(kMaxHeightFieldNodes),
                      rounded_up_cell(cell * std::sqrt(nx * ny / static_cast<double>(kMaxHeightFieldNodes)) * 1.01));
        throw Error(text);
    }
    DemGrid g;
    g.origin = {i0 * cell, j0 * cell};
    g.cell = cell;
    g.nx = static_cast<uint32_t>(nx);
    g.ny = static_cast<uint32_t>(ny);
    if (!height_field_within_limit(g.origin, g.cell, g.nx, g.ny))
        throw Error("the height field would reach beyond the scene's coordinate limits");
    g.heights.assign(g.size(), NAN);
    g.covered.assign(g.size(), 0);
    return g;
}

}  // namespace

double rounded_dem_cell(double metres) {
    if (!(metres > 1)) return 1;
    const double unit = std::pow(10.0, std::floor(std::log10(metres)) - 1);
    return std::round(metres / unit) * unit;
}

double default_field_cell(double dem_cell, const Box2& bounds) {
    const double cell = std::min(dem_cell, kRoadFitCell);
    const double span_x = bounds.max.x - bounds.min.x, span_y = bounds.max.y - bounds.min.y;
    const double margin = 2 * kDemMarginCells + 2;  // the grid's nodes beyond the bounds, and its rounding
    const auto nodes = [&](double c) { return (span_x / c + margin) * (span_y / c + margin); };
    if (nodes(cell) <= kDefaultFieldNodes) return cell;
    double coarse = rounded_up_cell(cell * std::sqrt(nodes(cell) / kDefaultFieldNodes));
    while (nodes(coarse) > kDefaultFieldNodes) coarse = rounded_up_cell(coarse * 1.01);
    return coarse;
}

void check_dem_files(const std::vector<std::string>& paths) {
    if (!paths.empty()) call(dem_module().check_files, paths);
}

DemRead read_dem(const DemRequest& request, const Projection& projection) {
    const DemModule& gdal = dem_module();
    double cell = request.cell;
    if (cell == 0) {
        call(gdal.native_cell, request.paths, projection.origin_lat(), projection.origin_lon(), cell);
        cell = default_field_cell(rounded_dem_cell(cell), request.bounds);
    }
    DemRead out;
    out.grid = grid_over(request.bounds, cell);
    call(gdal.warp, request.paths, projection.origin_lat(), projection.origin_lon(), out);
    if (out.files_used == 0) throw Error(no_overlap_message(out, request.bounds, projection));
    if (out.vertical_datum.empty()) out.vertical_datum = kAssumedVerticalDatum;
    return out;
}

}  // namespace citygen
