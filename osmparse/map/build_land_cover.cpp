#include "osmparse/map/build_land_cover.h"

#include <algorithm>
#include <cmath>

#include "common/scene_limits.h"
#include "osmparse/core/osm_units.h"
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

std::vector<Vec2> project_line(const std::vector<LatLon>& points, const Projection& projection) {
    std::vector<Vec2> line;
    for (const LatLon& p : points) line.push_back(projection.to_local(p.lat, p.lon));
    return line;
}

// A rectangle per segment of the line, `width` wide, reaching width / 2 past both ends.
std::vector<Ring> pier_strips(const std::vector<Vec2>& line, double width) {
    std::vector<Ring> strips;
    for (size_t k = 0; k + 1 < line.size(); ++k) {
        const Vec2 a = line[k], b = line[k + 1];
        if (!(length(b - a) > 0)) continue;
        const Vec2 u = normalize(b - a) * (0.5 * width), v = perp_left(u);
        Ring r{a - u - v, b + u - v, b + u + v, a - u + v};  // counter-clockwise
        for (Vec2& p : r) p = round_to_stored_precision(p);
        strips.push_back(std::move(r));
    }
    return strips;
}

}  // namespace

ReportKind land_cover_row(LandCoverClass c) {
    using K = ReportKind;
    static const ReportKind kRows[kLandCoverClassCount] = {  // in LandCoverClass order
        K::LandCoverWater, K::LandCoverSea,  K::LandCoverGreen,    K::LandCoverForest,
        K::LandCoverPaved, K::LandCoverSand, K::LandCoverFarmland, K::LandCoverBuiltUp,
    };
    return kRows[static_cast<int>(c)];
}

std::vector<LandCover> build_land_cover(const OsmData& osm, const Projection& projection,
                                        const BuildingParams& params, bool with_piers, ParseReport& report) {
    const ReportKind kind = ReportKind::LandCoverAreas;
    std::vector<LandCover> out;
    // Land cover keeps its shape: only edges turning by less than a degree are merged.
    BuildingParams clean = params;
    clean.simplify_angle_deg = std::min(params.simplify_angle_deg, 1.0);
    for (const OsmArea& area : osm.land_cover_areas) {
        const std::optional<LandCoverClass> cover = land_cover_class(area.tags);
        if (!cover || (!with_piers && is_pier(area.tags))) continue;
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
    if (with_piers) {
        int64_t untagged = 0;
        for (const OsmWay& line : osm.pier_lines) {
            std::optional<double> width = parse_osm_length(line.tags.get("width"));
            if (!width || *width < 1 || *width > 50) width = kLinearPierWidth, ++untagged;
            for (Ring& strip : pier_strips(project_line(line.locations, projection), *width)) {
                LandCover c;
                c.osm = {OsmType::Way, line.id};
                c.cover = LandCoverClass::Paved;
                c.outer = std::move(strip);
                out.push_back(std::move(c));
            }
        }
        if (untagged > 0) report.note(ReportKind::LandCoverPaved, ReportReason::PierLineWidthDefault, untagged);
    }
    std::stable_sort(out.begin(), out.end(), [](const LandCover& a, const LandCover& b) {
        return a.cover != b.cover ? a.cover < b.cover : a.osm < b.osm;
    });
    for (const LandCover& c : out) report.kept(land_cover_row(c.cover));
    report.kept(kind, static_cast<int64_t>(out.size()));
    return out;
}

namespace {

// The ring cut to the square of coordinates the scene limits allow (Sutherland-Hodgman: the
// square is convex), its new points at stored precision. Empty when nothing of it is inside.
Ring clip_to_coordinate_limit(const Ring& ring) {
    constexpr double kLimit = kMaxCoordinate;
    Ring cur = ring, next;
    for (int side = 0; side < 4 && !cur.empty(); ++side) {
        const bool along_x = side < 2;
        const double bound = side % 2 ? kLimit : -kLimit;
        auto value = [&](Vec2 p) { return along_x ? p.x : p.y; };
        auto inside = [&](Vec2 p) { return side % 2 ? value(p) <= bound : value(p) >= bound; };
        next.clear();
        for (size_t i = 0; i < cur.size(); ++i) {
            const Vec2 a = cur[i], b = cur[(i + 1) % cur.size()];
            if (inside(a)) next.push_back(a);
            if (inside(a) != inside(b)) {
                const double t = (bound - value(a)) / (value(b) - value(a));
                const Vec2 c = a + (b - a) * t;
                next.push_back(round_to_stored_precision(along_x ? Vec2{bound, c.y} : Vec2{c.x, bound}));
            }
        }
        std::swap(cur, next);
    }
    cur.erase(std::unique(cur.begin(), cur.end()), cur.end());
    while (cur.size() > 1 && cur.front() == cur.back()) cur.pop_back();
    return cur;
}

bool within_land_cover_limits(const Ring& ring) {
    return ring.size() <= kMaxLandCoverPoints && extent_within_limit(ring, kMaxLandCoverExtent) &&
           std::all_of(ring.begin(), ring.end(), [](Vec2 p) { return point_within_limit(p); });
}

bool finite_points(const Ring& ring) {
    return std::all_of(ring.begin(), ring.end(), [](Vec2 p) { return std::isfinite(p.x) && std::isfinite(p.y); });
}

// A ring the loader takes as an area: 3 points or more, not all on one line.
bool is_area(const Ring& ring) { return ring.size() >= 3 && std::fabs(signed_area(ring)) > 0; }

}  // namespace

// (Declared as dropping: it also clips, to the coordinate limit, what reaches beyond it.)
std::vector<LandCover> drop_land_cover_beyond_limits(std::vector<LandCover> cover, ParseReport& report) {
    std::vector<LandCover> kept;
    kept.reserve(cover.size());
    for (LandCover& c : cover) {
        const bool within = within_land_cover_limits(c.outer) &&
                            std::all_of(c.holes.begin(), c.holes.end(), within_land_cover_limits);
        if (!within) {
            // Too many points is a mapping accident: dropped. Beyond the coordinate limit (a
            // region reaching a thousand km out, an extract box of the whole world): the part
            // within is kept.
            bool ok = finite_points(c.outer) && c.outer.size() <= kMaxLandCoverPoints;
            for (const Ring& h : c.holes) ok = ok && finite_points(h) && h.size() <= kMaxLandCoverPoints;
            if (ok) {
                c.outer = clip_to_coordinate_limit(c.outer);
                std::vector<Ring> holes;
                for (const Ring& h : c.holes)
                    if (Ring clipped = clip_to_coordinate_limit(h); is_area(clipped)) holes.push_back(std::move(clipped));
                c.holes = std::move(holes);
                ok = is_area(c.outer) && within_land_cover_limits(c.outer) &&
                     std::all_of(c.holes.begin(), c.holes.end(), within_land_cover_limits);
            }
            if (!ok) {
                report.dropped(ReportKind::LandCoverAreas, ReportReason::BeyondSceneLimits);
                continue;
            }
            report.note(ReportKind::LandCoverAreas, ReportReason::ClippedAtSceneLimits);
        }
        kept.push_back(std::move(c));
    }
    return kept;
}

}  // namespace citygen
