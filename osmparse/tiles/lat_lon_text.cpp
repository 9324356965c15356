#include "osmparse/tiles/lat_lon_text.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <vector>

#include "common/error.h"

namespace citygen {

namespace {

// The comma-separated numbers of `text`, each finite and whole (no "7.7x", no empty item).
std::vector<double> numbers(const std::string& text, size_t count, const std::string& option, const char* form) {
    std::vector<double> out;
    size_t start = 0;
    while (true) {
        const size_t comma = text.find(',', start);
        const std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
        char* end = nullptr;
        errno = 0;
        const double v = std::strtod(item.c_str(), &end);
        if (item.empty() || *end != '\0' || errno != 0 || !std::isfinite(v))
            throw Error(option + ": '" + text + "' is not " + form);
        out.push_back(v);
        if (comma == std::string::npos) break;
        start = comma + 1;
    }
    if (out.size() != count) throw Error(option + ": '" + text + "' is not " + form);
    return out;
}

// The shortest text that reads back to v ("49.44", not "49.439999999999998").
std::string number_text(double v) {
    char text[32];
    for (int digits = 15; digits <= 17; ++digits) {
        std::snprintf(text, sizeof text, "%.*g", digits, v);
        if (std::strtod(text, nullptr) == v) break;
    }
    return text;
}

void check_range(LatLon p, const std::string& option) {
    if (p.lat < -90 || p.lat > 90) throw Error(option + ": latitude " + number_text(p.lat) + " is outside -90..90");
    if (p.lon < -180 || p.lon > 180) throw Error(option + ": longitude " + number_text(p.lon) + " is outside -180..180");
}

}  // namespace

LatLon parse_lat_lon(const std::string& text, const std::string& option) {
    const std::vector<double> v = numbers(text, 2, option, "LAT,LON (two numbers)");
    const LatLon p{v[0], v[1]};
    check_range(p, option);
    return p;
}

LatLonBox parse_lat_lon_box(const std::string& text, const std::string& option) {
    const std::vector<double> v = numbers(text, 4, option, "MINLAT,MINLON,MAXLAT,MAXLON (four numbers)");
    const LatLonBox box{{v[0], v[1]}, {v[2], v[3]}};
    check_range(box.min, option);
    check_range(box.max, option);
    if (!(box.min.lat < box.max.lat) || !(box.min.lon < box.max.lon))
        throw Error(option + ": '" + text + "' is empty (each minimum must be below its maximum)");
    return box;
}

std::string to_text(LatLon p) { return number_text(p.lat) + "," + number_text(p.lon); }

std::string to_text(const LatLonBox& box) { return to_text(box.min) + "," + to_text(box.max); }

}  // namespace citygen
