#include "osmparse/map/build_land_cover.h"

#include <algorithm>

#include "common/scene_limits.h"
#include "osmparse/polygons/clean_footprint.h"
#include "osmparse/read/land_cover_tags.h"
#include "osmparse/read/read_osm.h"

namespace citygen {

namespace {

Ring project_ring(const std::vector<LatLon>& points, const Projection& projection) {
    Ring ring;
    ring.reserve(points.size());
    for (const LatLon& p : points) ring.push_back(round_to_stored_precision(projection.to_local(p.lat, p.lon)));
    if (ring.size() > 1 && ring.front() == ring.back()) ring.pop_back();
    return ring;
}

}  // namespace

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
