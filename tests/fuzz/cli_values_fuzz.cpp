// Fuzzes the command-line value parsers: the first byte picks the parser, the rest is the
// value. Each must return a value within its limits or throw citygen::Error.
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "cli_values.h"
#include "error.h"
#include "geometry_mode.h"
#include "osm_units.h"
#include "scene_limits.h"
#include "sky.h"

using namespace citygen;

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size == 0) return 0;
    const std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
    try {
        switch (data[0] % 5) {
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
        }
    } catch (const Error&) {
    }
    return 0;
}
