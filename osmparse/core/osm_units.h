// Parsing of OSM length values, the one definition shared by heights and widths.
#pragma once

#include <optional>
#include <string>

namespace citygen {

// Parses an OSM length in metres: "12", "12.5", "12 m", "12m", "40 ft", "40'", "12'6\"",
// "3,5" (decimal comma). Returns nullopt for anything else (text, several values
// "3;4", negative numbers, NaN). Range checks are the caller's: they differ per tag.
std::optional<double> parse_osm_length(const char* text);

// Parses a non-negative count such as building:levels or lanes ("4", "4.5" -> 4.5).
std::optional<double> parse_osm_count(const char* text);

}  // namespace citygen
