#include "osmparse/map/assemble_sea.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

#include "osmparse/polygons/clean_footprint.h"
#include "osmparse/polygons/ring_bands.h"
#include "osmparse/read/read_osm.h"

namespace citygen {

namespace {

constexpr double kEdgeSnap = 0.5;  // metres: a chain end this close to the box edge lies on it

// Positions along the box boundary, counter-clockwise from the lower-left corner.
struct Boundary {
    Box2 box;
    double w, h;
    explicit Boundary(const Box2& b) : box(b), w(b.max.x - b.min.x), h(b.max.y - b.min.y) {}
    double perimeter() const { return 2 * (w + h); }
    double distance_to_edge(Vec2 p) const {
        return std::min({std::fabs(p.y - box.min.y), std::fabs(p.x - box.max.x), std::fabs(p.y - box.max.y),
                         std::fabs(p.x - box.min.x)});
    }
    // The point moved onto its nearest edge.
    Vec2 snap(Vec2 p) const {
        const double db = std::fabs(p.y - box.min.y), dr = std::fabs(p.x - box.max.x),
                     dt = std::fabs(p.y - box.max.y), dl = std::fabs(p.x - box.min.x);
        const double m = std::min({db, dr, dt, dl});
        const double x = std::clamp(p.x, box.min.x, box.max.x), y = std::clamp(p.y, box.min.y, box.max.y);
        if (m == db) return {x, box.min.y};
        if (m == dr) return {box.max.x, y};
        if (m == dt) return {x, box.max.y};
        return {box.min.x, y};
    }
    double position(Vec2 p) const {
        const double db = std::fabs(p.y - box.min.y), dr = std::fabs(p.x - box.max.x),
                     dt = std::fabs(p.y - box.max.y), dl = std::fabs(p.x - box.min.x);
        const double m = std::min({db, dr, dt, dl});
        if (m == db) return std::clamp(p.x - box.min.x, 0.0, w);
        if (m == dr) return w + std::clamp(p.y - box.min.y, 0.0, h);
        if (m == dt) return w + h + std::clamp(box.max.x - p.x, 0.0, w);
        return std::fmod(2 * w + h + std::clamp(box.max.y - p.y, 0.0, h), perimeter());
    }
    // Box corners met walking counter-clockwise from position a to position b.
    std::vector<Vec2> corners_between(double a, double b) const {
        const double P = perimeter();
        double span = std::fmod(b - a + 2 * P, P);
        const std::pair<double, Vec2> corners[4] = {{w, {box.max.x, box.min.y}},
                                                    {w + h, box.max},
                                                    {2 * w + h, {box.min.x, box.max.y}},
                                                    {0, box.min}};
        std::vector<std::pair<double, Vec2>> met;
        for (const auto& [c, p] : corners) {
            const double d = std::fmod(c - a + 2 * P, P);
            if (d > 0 && d < span) met.push_back({d, p});
        }
        std::sort(met.begin(), met.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
        std::vector<Vec2> out;
        for (const auto& m : met) out.push_back(m.second);
        return out;
    }
};

bool inside(const Box2& b, Vec2 p) { return p.x >= b.min.x && p.x <= b.max.x && p.y >= b.min.y && p.y <= b.max.y; }

// Liang-Barsky: the part [t0, t1] of segment a->b inside the box, false when none.
bool clip_segment(const Box2& b, Vec2 a, Vec2 d, double& t0, double& t1) {
    t0 = 0;
    t1 = 1;
    const double p[4] = {-d.x, d.x, -d.y, d.y};
    const double q[4] = {a.x - b.min.x, b.max.x - a.x, a.y - b.min.y, b.max.y - a.y};
    for (int i = 0; i < 4; ++i) {
        if (p[i] == 0) {
            if (q[i] < 0) return false;
            continue;
        }
        const double r = q[i] / p[i];
        if (p[i] < 0) t0 = std::max(t0, r);
        else t1 = std::min(t1, r);
    }
    return t0 <= t1;
}

// A part of a coastline chain inside the box.
struct Piece {
    std::vector<Vec2> points;
    int64_t way_id = 0;
    bool start_on_edge = false, end_on_edge = false;
};

// Cuts a chain into the pieces inside the box. A chain end inside the box (farther than
// kEdgeSnap from its edge) leaves its piece open at that end.
std::vector<Piece> clip_chain(const CoastlineChain& chain, const Boundary& boundary) {
    const Box2& box = boundary.box;
    std::vector<Piece> pieces;
    const std::vector<Vec2>& pts = chain.points;
    const bool closed = pts.size() > 2 && pts.front() == pts.back();
    Piece current;
    bool open = false;
    for (size_t i = 0; i + 1 < pts.size(); ++i) {
        const Vec2 a = pts[i], b = pts[i + 1];
        double t0, t1;
        if (!clip_segment(box, a, b - a, t0, t1)) continue;
        const Vec2 p0 = a + (b - a) * t0, p1 = a + (b - a) * t1;
        if (!open) {
            if (inside(box, a) && i > 0) continue;  // cannot happen: an inside point keeps a piece open
            if (!inside(box, a) && t0 == t1) continue;  // only touches the box
            current = Piece{};
            current.way_id = chain.way_id;
            const bool entering = !inside(box, a);
            const bool carried = !entering && i == 0 && chain.cut_before;
            current.start_on_edge = entering || carried || boundary.distance_to_edge(a) <= kEdgeSnap;
            if (carried && boundary.distance_to_edge(a) > kEdgeSnap) current.points.push_back(boundary.snap(a));
            current.points.push_back(current.start_on_edge && !carried ? boundary.snap(p0) : p0);
            open = true;
        }
        if (!inside(box, b)) {
            current.points.push_back(boundary.snap(p1));
            current.end_on_edge = true;
            pieces.push_back(std::move(current));
            open = false;
        } else {
            current.points.push_back(b);
        }
    }
    if (open) {
        const Vec2 last = current.points.back();
        current.end_on_edge = chain.cut_after || boundary.distance_to_edge(last) <= kEdgeSnap;
        if (boundary.distance_to_edge(last) <= kEdgeSnap) current.points.back() = boundary.snap(last);
        else if (chain.cut_after) current.points.push_back(boundary.snap(last));
        pieces.push_back(std::move(current));
    }
    // A closed chain that starts inside the box: its last and first pieces are one.
    if (closed && pieces.size() > 1 && !pieces.front().start_on_edge && !pieces.back().end_on_edge) {
        Piece& last = pieces.back();
        last.points.insert(last.points.end(), pieces.front().points.begin() + 1, pieces.front().points.end());
        last.end_on_edge = pieces.front().end_on_edge;
        pieces.erase(pieces.begin());
    }
    return pieces;
}

using TaggedRings = std::vector<std::pair<Ring, int64_t>>;  // rings with their coastline way

// The chains clipped to the box: pieces from edge to edge, and closed rings inside the box
// (islands, counter-clockwise as land is on the left; enclosed seas). False when a chain ends
// inside the box (counted).
bool clip_chains(const std::vector<CoastlineChain>& chains, const Boundary& boundary, std::vector<Piece>& open_pieces,
                 TaggedRings& islands, TaggedRings& enclosed, ParseReport& report) {
    for (const CoastlineChain& chain : chains) {
        for (Piece& piece : clip_chain(chain, boundary)) {
            const bool closed_ring = !piece.start_on_edge && !piece.end_on_edge && piece.points.size() > 3 &&
                                     piece.points.front() == piece.points.back();
            if (closed_ring) {
                Ring ring(piece.points.begin(), piece.points.end() - 1);
                (signed_area(ring) > 0 ? islands : enclosed).push_back({std::move(ring), piece.way_id});
                continue;
            }
            if (!piece.start_on_edge || !piece.end_on_edge) {
                report.dropped(ReportKind::SeaPolygons, ReportReason::CoastlineEndsInside);
                return false;
            }
            if (piece.points.size() >= 2) open_pieces.push_back(std::move(piece));
        }
    }
    return true;
}

// Water rings: every piece walked backwards (water on the left), then along the box edge
// counter-clockwise to the end of the next piece, and so on until the ring closes. False when
// the pieces do not close into rings (counted).
bool walk_water_rings(const std::vector<Piece>& open_pieces, const Boundary& boundary, TaggedRings& water,
                      ParseReport& report) {
    struct Event {
        double position;
        bool is_start;  // a piece's start (where a backwards walk ends) or its end
        size_t piece;
    };
    std::vector<Event> events;
    for (size_t k = 0; k < open_pieces.size(); ++k) {
        events.push_back({boundary.position(open_pieces[k].points.front()), true, k});
        events.push_back({boundary.position(open_pieces[k].points.back()), false, k});
    }
    std::sort(events.begin(), events.end(), [](const Event& a, const Event& b) {
        return a.position != b.position ? a.position < b.position : a.is_start > b.is_start;
    });
    std::vector<size_t> event_of_start(open_pieces.size());
    for (size_t i = 0; i < events.size(); ++i)
        if (events[i].is_start) event_of_start[events[i].piece] = i;
    std::vector<bool> used(open_pieces.size(), false);
    for (size_t first = 0; first < open_pieces.size(); ++first) {
        if (used[first]) continue;
        Ring ring;
        size_t k = first;
        for (size_t guard = 0; guard <= open_pieces.size(); ++guard) {
            used[k] = true;
            const std::vector<Vec2>& pts = open_pieces[k].points;
            ring.insert(ring.end(), pts.rbegin(), pts.rend());
            const Event& here = events[event_of_start[k]];
            const Event& next = events[(event_of_start[k] + 1) % events.size()];
            if (next.is_start) {
                report.dropped(ReportKind::SeaPolygons, ReportReason::CoastlineDirectionsDisagree);
                return false;
            }
            for (Vec2 c : boundary.corners_between(here.position, next.position)) ring.push_back(c);
            k = next.piece;
            if (k == first) break;
            if (used[k]) {
                report.dropped(ReportKind::SeaPolygons, ReportReason::CoastlineDoesNotClose);
                return false;
            }
        }
        water.push_back({std::move(ring), open_pieces[first].way_id});
    }
    return true;
}

// Cleans every water ring, then puts each island into the sea polygon around it.
std::vector<LandCover> sea_with_islands(TaggedRings& water, TaggedRings& islands, ParseReport& report) {
    BuildingParams clean;
    clean.simplify_angle_deg = 0;
    clean.min_area = 1;
    std::vector<LandCover> out;
    for (auto& [ring, id] : water)
        for (Footprint& f : clean_footprint(ring, {}, clean, report, ReportKind::SeaPolygons)) {
            LandCover c;
            c.osm = {OsmType::Way, id};
            c.cover = LandCoverClass::Sea;
            c.outer = std::move(f.outer);
            out.push_back(std::move(c));
        }
    for (auto& [ring, id] : islands) {
        std::vector<Footprint> cleaned = clean_footprint(ring, {}, clean, report, ReportKind::CoastlineIslands);
        for (Footprint& f : cleaned) {
            const Vec2 p = interior_point(f.outer);
            bool placed = false;
            for (LandCover& c : out)
                if (point_in_ring(p, c.outer)) {
                    std::reverse(f.outer.begin(), f.outer.end());  // holes are clockwise
                    c.holes.push_back(std::move(f.outer));
                    placed = true;
                    break;
                }
            if (!placed) report.dropped(ReportKind::CoastlineIslands, ReportReason::IslandNotInSea);
        }
    }
    // Holes must stay simple and apart: clean once more with them.
    std::vector<LandCover> final;
    for (LandCover& c : out) {
        if (c.holes.empty()) {
            final.push_back(std::move(c));
            continue;
        }
        for (Footprint& f : clean_footprint(c.outer, c.holes, clean, report, ReportKind::SeaPolygons))
            final.push_back({c.osm, LandCoverClass::Sea, std::move(f.outer), std::move(f.holes)});
    }
    return final;
}

}  // namespace

std::pair<LatLon, LatLon> extract_bounds(const OsmData& osm) {
    if (osm.has_extract_bounds) return {osm.extract_min, osm.extract_max};
    return {osm.min, osm.max};
}

Box2 extract_box(const OsmData& osm, const Projection& projection) {
    Box2 box;
    const auto [lo, hi] = extract_bounds(osm);
    if (lo.lat > hi.lat || lo.lon > hi.lon) return box;
    for (double lat : {lo.lat, hi.lat})
        for (double lon : {lo.lon, hi.lon}) box.extend(round_to_stored_precision(projection.to_local(lat, lon)));
    return box;
}

std::vector<LandCover> sea_from_chains(const std::vector<CoastlineChain>& chains, const Box2& box,
                                       ParseReport& report) {
    if (chains.empty() || box.empty()) return {};
    const Boundary boundary(box);
    std::vector<Piece> open_pieces;
    TaggedRings islands, enclosed, water;
    if (!clip_chains(chains, boundary, open_pieces, islands, enclosed, report)) return {};
    if (!walk_water_rings(open_pieces, boundary, water, report)) return {};
    // Closed rings only: islands in a box of sea (unless enclosed seas say otherwise).
    if (open_pieces.empty() && enclosed.empty() && !islands.empty())
        water.push_back({Ring{box.min, {box.max.x, box.min.y}, box.max, {box.min.x, box.max.y}}, islands.front().second});
    for (auto& [ring, id] : enclosed) {
        std::reverse(ring.begin(), ring.end());
        water.push_back({std::move(ring), id});
    }
    std::vector<LandCover> sea = sea_with_islands(water, islands, report);
    std::stable_sort(sea.begin(), sea.end(), [](const LandCover& a, const LandCover& b) { return a.osm < b.osm; });
    return sea;
}

std::vector<LandCover> assemble_sea(const OsmData& osm, const Projection& projection, const Box2& box,
                                    const std::vector<Building>& buildings, ParseReport& report) {
    if (osm.coastlines.empty()) return {};
    // Join the ways (directed: land on the left) into chains at shared end nodes.
    std::map<int64_t, size_t> by_start;
    std::set<int64_t> ends;
    for (size_t i = 0; i < osm.coastlines.size(); ++i) {
        if (!by_start.emplace(osm.coastlines[i].nodes.front(), i).second)
            report.note(ReportKind::CoastlineWays, ReportReason::TwoWaysStartAtOneNode);
        ends.insert(osm.coastlines[i].nodes.back());
    }
    std::vector<bool> used(osm.coastlines.size(), false);
    std::vector<CoastlineChain> chains;
    auto follow = [&](size_t i) {
        CoastlineChain chain;
        chain.way_id = osm.coastlines[i].id;
        chain.cut_before = osm.coastlines[i].cut_before;
        for (size_t k = i;;) {
            used[k] = true;
            const OsmWay& way = osm.coastlines[k];
            chain.cut_after = way.cut_after;
            for (size_t n = chain.points.empty() ? 0 : 1; n < way.locations.size(); ++n)
                chain.points.push_back(round_to_stored_precision(projection.to_local(way.locations[n].lat, way.locations[n].lon)));
            auto next = by_start.find(way.nodes.back());
            if (next == by_start.end() || used[next->second]) {
                // A ring closes on its first node: repeat the first point exactly.
                if (next != by_start.end() && next->second == i) chain.points.back() = chain.points.front();
                break;
            }
            k = next->second;
        }
        chains.push_back(std::move(chain));
    };
    for (size_t i = 0; i < osm.coastlines.size(); ++i)
        if (!used[i] && !ends.count(osm.coastlines[i].nodes.front())) follow(i);
    for (size_t i = 0; i < osm.coastlines.size(); ++i)
        if (!used[i]) follow(i);
    report.kept(ReportKind::CoastlineWays, static_cast<int64_t>(osm.coastlines.size()));
    for (const CoastlineChain& c : chains) {
        if (c.cut_before) report.note(ReportKind::CoastlineWays, ReportReason::CutByExtract);
        if (c.cut_after) report.note(ReportKind::CoastlineWays, ReportReason::CutByExtract);
    }
    report.read(ReportKind::SeaPolygons, static_cast<int64_t>(chains.size()));

    std::vector<LandCover> sea = sea_from_chains(chains, box, report);
    // Never a flooded city: a "sea" holding most buildings is land seen the wrong way round.
    std::vector<LandCover> kept;
    for (LandCover& c : sea) {
        // Every building against a sea of coastlines thousands of points long: banded.
        const RingBands outer(c.outer);
        std::vector<RingBands> holes;
        for (const Ring& hole : c.holes) holes.emplace_back(hole);
        auto in = [](Vec2 p, const Ring& ring, const RingBands& bands) {
            return bands.winding(ring, p, winding_step) != 0;
        };
        size_t wet = 0;
        for (const Building& b : buildings) {
            const Vec2 p = b.outer.front();
            if (!in(p, c.outer, outer)) continue;
            bool in_hole = false;
            for (size_t h = 0; h < c.holes.size(); ++h) in_hole = in_hole || in(p, c.holes[h], holes[h]);
            wet += !in_hole;
        }
        if (wet >= 10 && 2 * wet > buildings.size()) {
            report.dropped(ReportKind::SeaPolygons, ReportReason::WouldFloodCity);
            continue;
        }
        if (wet) report.note(ReportKind::SeaPolygons, ReportReason::BuildingsInSea, static_cast<int64_t>(wet));
        kept.push_back(std::move(c));
    }
    report.kept(ReportKind::SeaPolygons, static_cast<int64_t>(kept.size()));
    return kept;
}

}  // namespace citygen
