#include "osmparse/read/land_cover_tags.h"

#include <cstring>
#include <initializer_list>

namespace citygen {

namespace {

bool is_one_of(const char* value, std::initializer_list<const char*> values) {
    if (!value) return false;
    for (const char* v : values)
        if (!std::strcmp(value, v)) return true;
    return false;
}

}  // namespace

bool is_pier(const OsmTags& tags) {
    return is_one_of(tags.get("man_made"), {"pier", "breakwater"});
}

std::optional<LandCoverClass> land_cover_class(const OsmTags& tags) {
    const char* natural = tags.get("natural");
    const char* landuse = tags.get("landuse");
    const char* leisure = tags.get("leisure");
    if (is_one_of(natural, {"water"}) || tags.has("waterway", "riverbank") ||
        is_one_of(landuse, {"basin", "reservoir"}) || is_one_of(leisure, {"swimming_pool"}))
        return LandCoverClass::Water;
    if ((tags.has("highway", "pedestrian") && tags.has("area", "yes")) || tags.get("area:highway") ||
        tags.has("place", "square") || tags.has("amenity", "parking") || is_pier(tags))
        return LandCoverClass::Paved;
    if (is_one_of(natural, {"sand", "beach"})) return LandCoverClass::Sand;
    if (is_one_of(natural, {"wood"}) || is_one_of(landuse, {"forest"})) return LandCoverClass::Forest;
    if (is_one_of(leisure, {"park", "garden", "pitch", "playground"}) ||
        is_one_of(landuse, {"grass", "meadow", "village_green", "cemetery", "recreation_ground"}) ||
        is_one_of(natural, {"grassland", "heath", "scrub"}))
        return LandCoverClass::Green;
    if (is_one_of(landuse, {"farmland", "orchard", "vineyard", "allotments"})) return LandCoverClass::Farmland;
    if (is_one_of(landuse, {"residential", "commercial", "retail", "industrial"})) return LandCoverClass::BuiltUp;
    return std::nullopt;
}

const std::vector<const char*>& land_cover_keys() {
    static const std::vector<const char*> keys{"natural", "waterway", "landuse", "leisure",
                                               "highway", "area:highway", "place",   "amenity", "man_made"};
    return keys;
}

}  // namespace citygen
