#include "build_land_cover.h"

#include <algorithm>
#include <cstring>

#include "clean_footprint.h"
#include "read_osm.h"
#include "scene_limits.h"

namespace citygen {

namespace {

bool is_one_of(const char* value, std::initializer_list<const char*> values) {
    if (!value) return false;
    for (const char* v : values)
        if (!std::strcmp(value, v)) return true;
    return false;
}

Ring project_ring(const std::vector<LatLon>& points, const Projection& projection) {
    Ring ring;
    ring.reserve(points.size());
    for (const LatLon& p : points) ring.push_back(round_to_stored_precision(projection.to_local(p.lat, p.lon)));
    if (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
    return ring;
}

}  // namespace

std::optional<LandCoverClass> land_cover_class(const OsmTags& tags) {
    const char* natural = tags.get("natural");
    const char* landuse = tags.get("landuse");
    const char* leisure = tags.get("leisure");
    if (is_one_of(natural, {"water"}) || tags.has("waterway", "riverbank") ||
        is_one_of(landuse, {"basin", "reservoir"}) || is_one_of(leisure, {"swimming_pool"}))
        return LandCoverClass::Water;
    if ((tags.has("highway", "pedestrian") && tags.has("area", "yes")) || tags.get("area:highway") ||
        tags.has("place", "square") || tags.has("amenity", "parking"))
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
                                               "highway", "area:highway", "place",   "amenity"};
    return keys;
}

std::vector<LandCover> build_land_cover(const OsmData& osm, const Projection& projection,
                                        const BuildingParams& params, ParseReport& report) {
    const char* const kind = kLandCoverAreas;
    std::vector<LandCover> out;
    // Land cover keeps its shape: only edges turning by less than a degree are merged.
    BuildingParams clean = params;
    clean.simplify_angle_deg = std::min(params.simplify_angle_deg, 1.0);
    for (const OsmArea& area : osm.land_cover_areas) {
        const std::optional<LandCoverClass> cover = land_cover_class(area.tags);
        if (!cover) continue;
        for (const OsmPolygon& polygon : area.polygons) {
            std::vector<Ring> holes;
            for (const std::vector<LatLon>& inner : polygon.inners) holes.push_back(project_ring(inner, projection));
            for (Footprint& f : clean_footprint(project_ring(polygon.outer, projection), holes, clean, report, kind)) {
                LandCover c;
                c.osm = area.ref;
                c.cover = *cover;
                c.outer = std::move(f.outer);
                c.holes = std::move(f.holes);
                out.push_back(std::move(c));
            }
        }
    }
    std::stable_sort(out.begin(), out.end(), [](const LandCover& a, const LandCover& b) {
        return a.cover != b.cover ? a.cover < b.cover : a.osm < b.osm;
    });
    for (const LandCover& c : out) report.kept(std::string(kLandCoverClassPrefix) + to_string(c.cover));
    report.kept(kind, static_cast<int64_t>(out.size()));
    return out;
}

std::vector<LandCover> drop_land_cover_beyond_limits(std::vector<LandCover> cover, ParseReport& report) {
    auto beyond = [](const Ring& ring) {
        const Box2 box = bounds_of(ring);
        return ring.size() > kMaxLandCoverPoints ||
               (!box.empty() && std::max(box.max.x - box.min.x, box.max.y - box.min.y) > kMaxLandCoverExtent);
    };
    std::vector<LandCover> kept;
    kept.reserve(cover.size());
    for (LandCover& c : cover) {
        if (beyond(c.outer) || std::any_of(c.holes.begin(), c.holes.end(), beyond))
            report.dropped(kLandCoverAreas, kBeyondSceneLimits);
        else
            kept.push_back(std::move(c));
    }
    return kept;
}

}  // namespace citygen
