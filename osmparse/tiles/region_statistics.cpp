#include "osmparse/tiles/region_statistics.h"

#include <cerrno>
#include <climits>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iterator>
#include <sstream>

#include <sys/stat.h>

#include "common/error.h"
#include "common/scene_io.h"

namespace citygen {

namespace {

constexpr const char* kHeader = "citygen-region-statistics 1";
// Bounds that every value the writer can be given passes (a tagged height is above 0 and at
// most BuildingParams::max_height; a log ratio of two positive doubles is within 745 of 0),
// while a corrupt file cannot make a median infinite.
constexpr double kMaxHeight = 10000;
constexpr double kMaxLogRatio = 1000;
constexpr size_t kMaxTypeLength = 1024;  // bytes: OSM's 255 characters of up to 4 bytes each

std::string hex_float(double v) {
    char text[40];
    std::snprintf(text, sizeof text, "%a", v);
    return text;
}

bool plain(unsigned char c) { return c > ' ' && c != '%' && c != 0x7f; }

std::string encode_type(const std::string& type) {
    std::string out;
    for (unsigned char c : type) {
        if (plain(c)) {
            out += static_cast<char>(c);
        } else {
            char escaped[4];
            std::snprintf(escaped, sizeof escaped, "%%%02X", c);
            out += escaped;
        }
    }
    return out;
}

int hex_digit(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

// Reads the fields of one line, each check naming the file and line on failure.
class LineReader {
public:
    LineReader(const std::string& line, const std::string& path, size_t number)
        : in_(line), where_(path + ": line " + std::to_string(number) + ": ") {}

    std::string word() {
        std::string w;
        if (!(in_ >> w)) fail("too few fields");
        return w;
    }
    long long integer(long long min, long long max, const char* what) {
        const std::string w = word();
        char* end = nullptr;
        errno = 0;
        const long long v = std::strtoll(w.c_str(), &end, 10);
        if (*end != '\0' || errno != 0 || v < min || v > max)
            fail(std::string(what) + " '" + w + "' is not a whole number in " + std::to_string(min) + ".." +
                 std::to_string(max));
        return v;
    }
    double number(double min, double max, const char* what) {
        const std::string w = word();
        char* end = nullptr;
        const double v = std::strtod(w.c_str(), &end);  // overflow gives inf; underflow, a denormal or 0
        if (*end != '\0' || !std::isfinite(v) || v < min || v > max)
            fail(std::string(what) + " '" + w + "' is not a number in range");
        return v;
    }
    std::string type() {
        const std::string w = word();
        std::string out;
        for (size_t i = 0; i < w.size(); ++i) {
            if (w[i] != '%') {
                out += w[i];
                continue;
            }
            const int hi = i + 2 < w.size() ? hex_digit(w[i + 1]) : -1;
            const int lo = hi >= 0 ? hex_digit(w[i + 2]) : -1;
            if (lo < 0) fail("bad %XX escape in type '" + w + "'");
            out += static_cast<char>(hi * 16 + lo);
            i += 2;
        }
        if (out.size() > kMaxTypeLength) fail("type longer than " + std::to_string(kMaxTypeLength) + " bytes");
        return out;
    }
    void done() {
        std::string rest;
        if (in_ >> rest) fail("unexpected field '" + rest + "'");
    }
    [[noreturn]] void fail(const std::string& what) const { throw Error(where_ + what); }

private:
    std::istringstream in_;
    std::string where_;
};

}  // namespace

std::string region_statistics_text(const RegionStatistics& s) {
    std::string out = std::string(kHeader) + "\n";
    size_t records = 0;
    for (const HeightEvidence::Tagged& t : s.heights.tagged) {
        out += "tagged " + std::to_string(t.area_class) + " " + hex_float(t.height) + " " + encode_type(t.type) + "\n";
        ++records;
    }
    for (const HeightEvidence::Ratio& r : s.heights.calibration) {
        out += "ratio " + std::to_string(r.group) + " " + hex_float(r.log_ratio) + "\n";
        ++records;
    }
    for (int g = 0; g < static_cast<int>(RoofGroup::Count); ++g) {
        if (s.roofs.tagged[g] == 0) continue;
        out += "roofs " + std::to_string(g) + " " + std::to_string(s.roofs.tagged[g]) + " " +
               std::to_string(s.roofs.pitched[g]) + "\n";
        ++records;
    }
    return out + "end " + std::to_string(records) + "\n";
}

RegionStatistics parse_region_statistics(const std::string& text, const std::string& path) {
    RegionStatistics s;
    long long roof_tagged[static_cast<int>(RoofGroup::Count)] = {}, roof_pitched[static_cast<int>(RoofGroup::Count)] = {};
    std::istringstream in(text);
    bool in_part = false;
    size_t number = 0, parts = 0;
    long long records = 0;
    for (std::string line; std::getline(in, line);) {
        LineReader r(line, path, ++number);
        if (line == kHeader) {
            if (in_part) r.fail("a part opens before the last one ended (a cut file?)");
            in_part = true;
            records = 0;
            continue;
        }
        if (!in_part) r.fail("expected '" + std::string(kHeader) + "' (not a region statistics file?)");
        const std::string kind = r.word();
        if (kind == "tagged") {
            HeightEvidence::Tagged t;
            t.area_class = static_cast<int>(r.integer(0, HeightEvidence::kFootprintClasses - 1, "footprint class"));
            t.height = r.number(0, kMaxHeight, "height");
            if (!(t.height > 0)) r.fail("height 0: a tagged height is above 0");
            t.type = r.type();
            s.heights.tagged.push_back(std::move(t));
        } else if (kind == "ratio") {
            HeightEvidence::Ratio ratio;
            ratio.group = static_cast<int>(r.integer(0, HeightEvidence::kCalibratedGroups - 1, "group"));
            ratio.log_ratio = r.number(-kMaxLogRatio, kMaxLogRatio, "ratio");
            s.heights.calibration.push_back(ratio);
        } else if (kind == "roofs") {
            const int g = static_cast<int>(r.integer(0, static_cast<int>(RoofGroup::Count) - 1, "roof group"));
            const long long tagged = r.integer(0, INT_MAX, "count");
            const long long pitched = r.integer(0, tagged, "pitched count");
            roof_tagged[g] += tagged;
            roof_pitched[g] += pitched;
            if (roof_tagged[g] > INT_MAX) r.fail("roof counts beyond " + std::to_string(INT_MAX));
        } else if (kind == "end") {
            r.integer(records, records, "record count");
            in_part = false;
            ++parts;
        } else {
            r.fail("unknown record '" + kind + "'");
        }
        r.done();
        if (kind != "end") ++records;
    }
    if (in_part) throw Error(path + ": cut short (the last part has no 'end' line)");
    if (parts == 0) throw Error(path + ": empty (no region statistics in it)");
    for (int g = 0; g < static_cast<int>(RoofGroup::Count); ++g) {
        s.roofs.tagged[g] = static_cast<int>(roof_tagged[g]);
        s.roofs.pitched[g] = static_cast<int>(roof_pitched[g]);
    }
    return s;
}

RegionStatistics read_region_statistics(const std::vector<std::string>& paths) {
    std::string text;
    for (const std::string& path : paths) {
        struct stat info;
        if (::stat(path.c_str(), &info) == 0 && S_ISDIR(info.st_mode)) throw Error(path + ": a directory, not a file");
        std::ifstream in(path, std::ios::binary);
        if (!in) throw Error(path + ": cannot open");
        const std::string part((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        if (in.bad()) throw Error(path + ": cannot read");
        parse_region_statistics(part, path);  // each file whole, each error naming its file
        text += part;
        if (!part.empty() && part.back() != '\n') text += '\n';
    }
    return parse_region_statistics(text, paths.size() == 1 ? paths.front() : "the region statistics");
}

void write_region_statistics(const std::string& path, const RegionStatistics& statistics) {
    const std::string text = region_statistics_text(statistics);
    write_file_atomically(path, text.data(), text.size(), [&] { parse_region_statistics(text, path); });
}

}  // namespace citygen
