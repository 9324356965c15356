#include "osmparse/core/osm_units.h"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <cstring>

namespace citygen {

namespace {

constexpr double kFoot = 0.3048;
constexpr double kInch = 0.0254;

void skip_spaces(const char*& p) {
    while (*p && std::isspace(static_cast<unsigned char>(*p))) ++p;
}

// Reads an unsigned decimal number with '.' or a single ',' as decimal mark.
std::optional<double> read_number(const char*& p) {
    std::string digits;
    bool seen_mark = false;
    while (*p) {
        const char c = *p;
        if (std::isdigit(static_cast<unsigned char>(c))) {
            digits += c;
        } else if ((c == '.' || c == ',') && !seen_mark) {
            digits += '.';
            seen_mark = true;
        } else {
            break;
        }
        ++p;
    }
    if (digits.empty() || digits == ".") return std::nullopt;
    return std::strtod(digits.c_str(), nullptr);
}

}  // namespace

std::optional<double> parse_osm_length(const char* text) {
    if (!text) return std::nullopt;
    const char* p = text;
    skip_spaces(p);
    std::optional<double> value = read_number(p);
    if (!value) return std::nullopt;
    skip_spaces(p);
    double metres = *value;
    if (*p == '\'') {  // feet, optionally followed by inches: 12'6"
        ++p;
        metres = *value * kFoot;
        skip_spaces(p);
        if (*p) {
            std::optional<double> inches = read_number(p);
            if (!inches || *p != '"') return std::nullopt;
            ++p;
            metres += *inches * kInch;
        }
    } else if (*p == '"') {
        ++p;
        metres = *value * kInch;
    } else if (std::strncmp(p, "feet", 4) == 0 || std::strncmp(p, "ft", 2) == 0) {
        p += p[1] == 'e' ? 4 : 2;
        metres = *value * kFoot;
    } else if (std::strncmp(p, "mi", 2) == 0) {
        return std::nullopt;  // miles are not a building or road length
    } else if (std::strncmp(p, "km", 2) == 0) {
        p += 2;
        metres = *value * 1000;
    } else if (std::strncmp(p, "cm", 2) == 0) {
        p += 2;
        metres = *value / 100;
    } else if (*p == 'm') {
        ++p;
    }
    skip_spaces(p);
    if (*p || !std::isfinite(metres)) return std::nullopt;
    return metres;
}

std::optional<double> parse_osm_count(const char* text) {
    if (!text) return std::nullopt;
    const char* p = text;
    skip_spaces(p);
    std::optional<double> value = read_number(p);
    skip_spaces(p);
    if (!value || *p || !std::isfinite(*value)) return std::nullopt;
    return value;
}

}  // namespace citygen
