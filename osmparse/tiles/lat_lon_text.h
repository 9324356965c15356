// The tile options' values as text: --origin LAT,LON and --keep-inside MINLAT,MINLON,MAXLAT,MAXLON.
#pragma once

#include <string>

#include "osmparse/core/osm_data.h"

namespace citygen {

// A box in degrees, half-open: it holds (lat, lon) when min <= lat < max and min <= lon < max, so
// boxes that share an edge, as the tiles of a region do, never both hold a point.
struct LatLonBox {
    LatLon min, max;
    bool contains(LatLon p) const { return p.lat >= min.lat && p.lat < max.lat && p.lon >= min.lon && p.lon < max.lon; }
};

// "49.44,7.76": a latitude in -90..90 and a longitude in -180..180; throws Error naming `option`.
LatLon parse_lat_lon(const std::string& text, const std::string& option);
// "MINLAT,MINLON,MAXLAT,MAXLON" with min < max on each axis; throws Error naming `option`.
LatLonBox parse_lat_lon_box(const std::string& text, const std::string& option);
// Texts that parse_lat_lon and parse_lat_lon_box read back to the same values.
std::string to_text(const LatLonBox& box);
std::string to_text(LatLon p);

}  // namespace citygen
