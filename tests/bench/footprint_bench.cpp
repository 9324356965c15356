// Footprint benchmark, run by hand (never from ctest): for every building footprint of the
// given extracts, each footprint operation as osmparse does it (hand-written float code where
// it stays) beside CGAL's variant (osmparse/polygons/cgal_footprint.h), medians of 5 runs, and how often
// the two disagree.
//
//   build/bin/footprint_bench [FILE.osm ...]   (default: Monaco and Kaiserslautern)
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

#include "common/projection.h"
#include "osmparse/polygons/cgal_footprint.h"
#include "osmparse/polygons/clean_footprint.h"
#include "osmparse/polygons/polygon_overlap.h"
#include "osmparse/polygons/ring_is_simple.h"
#include "osmparse/read/read_osm.h"

using namespace citygen;

namespace {

struct Polygon {
    Ring outer;
    std::vector<Ring> holes;
};

Ring project(const std::vector<LatLon>& points, const Projection& projection) {
    Ring ring;
    for (size_t i = 0; i + 1 < points.size(); ++i)  // closed: the last point repeats the first
        ring.push_back(round_to_stored_precision(projection.to_local(points[i].lat, points[i].lon)));
    return ring;
}

// Median milliseconds of 5 runs of f.
double median_ms(const std::function<void()>& f) {
    std::vector<double> times;
    for (int run = 0; run < 5; ++run) {
        const auto start = std::chrono::steady_clock::now();
        f();
        times.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count());
    }
    std::sort(times.begin(), times.end());
    return times[2];
}

void row(const char* operation, size_t count, double hand_ms, double cgal_ms, const std::string& agreement) {
    std::printf("  %-34s %9zu %12.2f %12.2f %8.1fx   %s\n", operation, count, hand_ms, cgal_ms, cgal_ms / hand_ms,
                agreement.c_str());
}

void bench(const std::string& path) {
    ParseReport report;
    const OsmData osm = read_osm(path, true, report);
    const Projection projection(0.5 * (osm.min.lat + osm.max.lat), 0.5 * (osm.min.lon + osm.max.lon));
    std::vector<Polygon> raw;
    for (const OsmArea& area : osm.building_areas)
        for (const OsmPolygon& p : area.polygons) {
            Polygon polygon{project(p.outer, projection), {}};
            for (const auto& inner : p.inners) polygon.holes.push_back(project(inner, projection));
            raw.push_back(std::move(polygon));
        }
    // Rings as clean_footprint sees them after step 1, and the simple ones among them.
    std::vector<Ring> rings, simple;
    std::vector<Polygon> simple_polygons;  // every ring simple
    for (const Polygon& p : raw) {
        Polygon cleaned{remove_repeated_and_collinear(p.outer), {}};
        bool all_simple = ring_is_simple(cleaned.outer);
        rings.push_back(cleaned.outer);
        for (const Ring& h : p.holes) {
            cleaned.holes.push_back(remove_repeated_and_collinear(h));
            rings.push_back(cleaned.holes.back());
            all_simple &= ring_is_simple(cleaned.holes.back());
        }
        if (all_simple) simple_polygons.push_back(cleaned);
    }
    std::vector<Ring> not_simple;
    for (const Ring& r : rings) (ring_is_simple(r) ? simple : not_simple).push_back(r);
    std::printf("%s: %zu footprints, %zu rings (%zu not simple)\n", path.c_str(), raw.size(), rings.size(), not_simple.size());
    std::printf("  %-34s %9s %12s %12s %9s   %s\n", "operation", "count", "hand ms", "CGAL ms", "CGAL/hand", "disagreements");

    // Validity: pairwise below 33 points, CGAL's sweep above (ring_is_simple) vs the sweep for all.
    size_t differ = 0;
    for (const Ring& r : rings) differ += ring_is_simple(r) != ring_is_simple_sweep(r);
    volatile size_t sink = 0;
    row("validity (ring_is_simple)", rings.size(),
        median_ms([&] { for (const Ring& r : rings) sink = sink + ring_is_simple(r); }),
        median_ms([&] { for (const Ring& r : rings) sink = sink + ring_is_simple_sweep(r); }),
        std::to_string(differ) + " rings");

    // Orientation: sign of the shoelace area vs CGAL::orientation_2.
    differ = 0;
    for (const Ring& r : simple) differ += (signed_area(r) > 0 ? 1 : -1) != ring_orientation_exact(r);
    row("orientation", simple.size(),
        median_ms([&] { for (const Ring& r : simple) sink = sink + (signed_area(r) > 0); }),
        median_ms([&] { for (const Ring& r : simple) sink = sink + (ring_orientation_exact(r) > 0); }),
        std::to_string(differ) + " rings");

    // Simplification of each polygon: merge_small_turns ring by ring (kept if simple) vs CGAL's
    // topology-keeping simplification of all its rings together.
    const double angle = BuildingParams{}.simplify_angle_deg;
    auto merged_alone = [&](const Ring& r) {
        Ring m = remove_repeated_and_collinear(merge_small_turns(r, angle));
        return m.size() >= 3 && ring_is_simple(m) ? m : r;
    };
    size_t rings_differ = 0, points_hand = 0, points_cgal = 0, total_rings = 0;
    for (const Polygon& p : simple_polygons) {
        std::vector<Ring> together{p.outer};
        together.insert(together.end(), p.holes.begin(), p.holes.end());
        const std::vector<Ring> cgal = simplify_keeping_topology(together, angle);
        for (size_t i = 0; i < together.size(); ++i) {
            const Ring hand = merged_alone(together[i]);
            const Ring exact = remove_repeated_and_collinear(cgal[i]);
            rings_differ += hand != exact;
            points_hand += hand.size();
            points_cgal += exact.size();
            ++total_rings;
        }
    }
    row("simplification", simple_polygons.size(),
        median_ms([&] {
            for (const Polygon& p : simple_polygons) {
                sink = sink + merged_alone(p.outer).size();
                for (const Ring& h : p.holes) sink = sink + merged_alone(h).size();
            }
        }),
        median_ms([&] {
            for (const Polygon& p : simple_polygons) {
                std::vector<Ring> together{p.outer};
                together.insert(together.end(), p.holes.begin(), p.holes.end());
                sink = sink + simplify_keeping_topology(together, angle).size();
            }
        }),
        std::to_string(rings_differ) + " of " + std::to_string(total_rings) + " rings differ; points kept " +
            std::to_string(points_hand) + " hand, " + std::to_string(points_cgal) + " CGAL");

    // Splitting: only CGAL's arrangement remains (the float split it replaced is gone).
    size_t pieces = 0;
    const double split_ms = median_ms([&] {
        pieces = 0;
        for (const Ring& r : not_simple) pieces += split_self_intersections(r).size();
    });
    std::printf("  %-34s %9zu %12s %12.2f %9s   %zu pieces\n", "split self-intersecting rings", not_simple.size(), "-",
                split_ms, "-", pieces);

    // The whole clean-up as the buildings stage runs it.
    const double clean_ms = median_ms([&] {
        ParseReport r;
        for (const Polygon& p : raw)
            sink = sink + clean_footprint(p.outer, p.holes, BuildingParams{}, r, ReportKind::Buildings).size();
    });
    std::printf("  %-34s %9zu %12.2f %12s %9s\n", "clean_footprint (as osmparse runs it)", raw.size(), clean_ms, "", "");

    // Overlap of a road-like 20 x 6 m quad across each footprint's first edge with the footprint.
    std::vector<Building> buildings;
    std::vector<Ring> quads;
    {
        ParseReport r;
        for (const Polygon& p : raw)
            for (Footprint& f : clean_footprint(p.outer, p.holes, BuildingParams{}, r, ReportKind::Buildings)) {
                const Vec2 a = f.outer[0], b = f.outer[1], mid = (a + b) * 0.5;
                const Vec2 along = (b - a) * (1 / length(b - a)), across{-along.y, along.x};
                quads.push_back({mid - along * 10 - across * 3, mid + along * 10 - across * 3,
                                 mid + along * 10 + across * 3, mid - along * 10 + across * 3});
                Building building;
                building.outer = std::move(f.outer);
                building.holes = std::move(f.holes);
                buildings.push_back(std::move(building));
            }
    }
    double worst = 0;
    for (size_t i = 0; i < buildings.size(); ++i)
        worst = std::max(worst, std::fabs(overlap_area(quads[i], buildings[i]) -
                                          overlap_area_exact(quads[i], buildings[i].outer, buildings[i].holes)));
    char agreement[64];
    std::snprintf(agreement, sizeof agreement, "largest difference %.2g m2", worst);
    row("overlap area (quad vs footprint)", buildings.size(),
        median_ms([&] { for (size_t i = 0; i < buildings.size(); ++i) sink = sink + overlap_area(quads[i], buildings[i]); }),
        median_ms([&] {
            for (size_t i = 0; i < buildings.size(); ++i)
                sink = sink + overlap_area_exact(quads[i], buildings[i].outer, buildings[i].holes);
        }),
        agreement);
}

}  // namespace

int main(int argc, char** argv) {
    std::vector<std::string> files(argv + 1, argv + argc);
    if (files.empty())
        files = {std::string(CITYGEN_SHARED_DATA_DIR) + "/monaco.osm.bz2",
                 std::string(CITYGEN_SHARED_DATA_DIR) + "/kaiserslautern.osm.gz"};
    for (const std::string& f : files) bench(f);
    return 0;
}
