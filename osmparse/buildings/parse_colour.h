// OSM colour values: CSS colour names, #rgb and #rrggbb (what building:colour and roof:colour use).
#pragma once

#include <cstdint>

namespace citygen {

// The colour as 0xRRGGBB (sRGB), or false for anything else ("blurple", "#12345", "red;blue").
// Case-insensitive; spaces, underscores and hyphens inside names are ignored ("light grey",
// "dark_red"), and "grey" spellings are accepted like "gray".
bool parse_colour(const char* text, uint32_t* rgb);

}  // namespace citygen
