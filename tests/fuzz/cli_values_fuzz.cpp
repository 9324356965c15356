// Fuzzes the command-line value parsers and the small text files options name: the first byte
// picks the parser, the rest is the value. Each must return a value within its limits or throw
// citygen::Error.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "common/error.h"
#include "common/scene_limits.h"
#include "osmparse/core/osm_units.h"
#include "osmparse/tiles/region_statistics.h"
#include "render/camera/camera_path.h"
#include "render/cli_values.h"
#include "render/lights/sky.h"
#include "render/scene/geometry_mode.h"

using namespace citygen;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size == 0) return 0;
    const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
    try {
        switch (data[0] % 9) {
            case 0: {
                const Vec3 p = parse_point(text, "--camera");
                if (!(std::fabs(p.x) <= kMaxCoordinate && std::fabs(p.y) <= kMaxCoordinate &&
                      std::fabs(p.z) <= kMaxCoordinate))
                    std::abort();
                check_view(p, parse_point(text, "--look-at"));
                break;
            }
            case 1: parse_geometry_mode(text, "--geometry-buildings"); break;
            case 2: parse_time_of_day(text); break;
            case 3: {  // OSM tag values (C strings: up to the first NUL)
                const std::optional<double> v = parse_osm_length(text.c_str());
                if (v && !std::isfinite(*v)) std::abort();
                break;
            }
            case 4: {
                const std::optional<double> v = parse_osm_count(text.c_str());
                if (v && !std::isfinite(*v)) std::abort();
                break;
            }
            case 5: {
                const PixelRegion r = parse_region(text);
                if (r.empty()) std::abort();
                break;
            }
            case 6: {  // a camera path file's text: every key within the limits, times increasing
                const CameraPath path = parse_camera_path(text, "path.csv");
                if (path.keys.size() < 2) std::abort();
                for (const CameraKey& k : path.keys)
                    if (!(k.time >= 0 && k.time <= kMaxPathSeconds) || std::fabs(k.position.x) > kMaxCoordinate ||
                        std::fabs(k.look_at.z) > kMaxCoordinate)
                        std::abort();
                camera_path_at(path, path.keys.front().time + 0.5 * (path.keys.back().time - path.keys.front().time));
                break;
            }
            case 7: parse_frame_range(text); break;
            case 8: {  // a farm's region statistics (--region-statistics): what the rules read stays finite
                const RegionStatistics s = parse_region_statistics(text, "region.stats");
                for (const HeightEvidence::Tagged& t : s.heights.tagged)
                    if (!(t.height > 0 && std::isfinite(t.height)) || t.area_class < 0 ||
                        t.area_class >= HeightEvidence::kFootprintClasses)
                        std::abort();
                for (const HeightEvidence::Ratio& r : s.heights.calibration)
                    if (!std::isfinite(r.log_ratio) || r.group < 0 || r.group >= HeightEvidence::kCalibratedGroups)
                        std::abort();
                for (int g = 0; g < static_cast<int>(RoofGroup::Count); ++g)
                    if (s.roofs.tagged[g] < 0 || s.roofs.pitched[g] < 0 || s.roofs.pitched[g] > s.roofs.tagged[g])
                        std::abort();
                break;
            }
        }
    } catch (const Error&) {
    }
    return 0;
}
