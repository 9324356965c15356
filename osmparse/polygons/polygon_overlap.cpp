#include "osmparse/polygons/polygon_overlap.h"

#include <algorithm>
#include <cmath>

#include "osmparse/polygons/exact_predicates.h"

namespace citygen {

namespace {
// One Sutherland-Hodgman step: the part of `poly` left of the line a->b, into `out`. The float
// side test stays: it builds an area, and a point within rounding of the line adds nothing to
// it whichever side it goes (the exact sign could disagree with dp's and put t outside [0, 1]).
void clip_to_left_of(const Ring& poly, Vec2 a, Vec2 b, Ring& out) {
    out.clear();
    for (size_t j = 0, m = poly.size(); j < m; ++j) {
        const Vec2 p = poly[j], q = poly[(j + 1) % m];
        const double dp = cross(b - a, p - a), dq = cross(b - a, q - a);
        if (dp >= 0) out.push_back(p);
        if ((dp >= 0) != (dq >= 0)) out.push_back(p + (q - p) * (dp / (dp - dq)));
    }
}
}  // namespace

double clipped_area(const Ring& subject, const Ring& clip) {
    const size_t n = clip.size();
    if (n < 3 || subject.size() < 3) return 0;
    const bool ccw = signed_area(clip) > 0;
    auto edge = [&](size_t i, Vec2& a, Vec2& b) {  // clip edges with the inside on the left
        a = clip[ccw ? i : (n - i) % n];
        b = clip[ccw ? (i + 1) % n : (2 * n - i - 1) % n];
    };
    // Most candidate pairs only touch: one clip edge with the whole subject outside it.
    for (size_t i = 0; i < n; ++i) {
        Vec2 a, b;
        edge(i, a, b);
        bool all_outside = true;
        for (Vec2 p : subject)
            if (exact_orientation(a, b, p) > 0) {
                all_outside = false;
                break;
            }
        if (all_outside) return 0;
    }
    // Sutherland-Hodgman, ping-ponging between two buffers.
    thread_local Ring poly, out;
    poly.assign(subject.begin(), subject.end());
    for (size_t i = 0; i < n && !poly.empty(); ++i) {
        Vec2 a, b;
        edge(i, a, b);
        clip_to_left_of(poly, a, b, out);
        poly.swap(out);
    }
    return poly.size() < 3 ? 0.0 : std::fabs(signed_area(poly));
}

Ring clip_to_half_planes(const Ring& subject, const std::vector<std::pair<Vec2, Vec2>>& lines) {
    Ring poly = subject, out;
    for (const auto& [a, b] : lines) {
        clip_to_left_of(poly, a, b, out);
        poly.swap(out);
        if (poly.size() < 3) return {};
    }
    return poly;
}

std::vector<Ring> triangulate(const Ring& polygon) {
    std::vector<Vec2> p = polygon;
    if (signed_area(p) < 0) std::reverse(p.begin(), p.end());
    std::vector<Ring> out;
    size_t guard = 0;
    while (p.size() > 3 && guard++ < 10000) {
        const size_t n = p.size();
        bool clipped = false;
        for (size_t i = 0; i < n; ++i) {
            const Vec2 a = p[(i + n - 1) % n], b = p[i], c = p[(i + 1) % n];
            if (exact_orientation(a, b, c) <= 0) continue;  // reflex or flat: not an ear
            bool empty = true;
            for (size_t j = 0; j < n && empty; ++j) {
                if (j == i || j == (i + 1) % n || j == (i + n - 1) % n) continue;
                const Vec2 q = p[j];
                if (exact_orientation(a, b, q) >= 0 && exact_orientation(b, c, q) >= 0 && exact_orientation(c, a, q) >= 0)
                    empty = false;
            }
            if (!empty) continue;
            out.push_back({a, b, c});
            p.erase(p.begin() + static_cast<long>(i));
            clipped = true;
            break;
        }
        if (!clipped) {  // only flat or numerically tricky corners left: drop one
            size_t flat = 0;
            double best = 1e300;
            for (size_t i = 0; i < n; ++i) {
                const double c = std::fabs(cross(p[i] - p[(i + n - 1) % n], p[(i + 1) % n] - p[i]));
                if (c < best) best = c, flat = i;
            }
            p.erase(p.begin() + static_cast<long>(flat));
        }
    }
    if (p.size() == 3 && signed_area(p) > 0) out.push_back(p);
    return out;
}

double overlap_area(const Ring& piece, const PolygonRef& b) {
    auto inside_footprint = [&](const Ring& convex) {
        double a = clipped_area(*b.outer, convex);
        if (b.holes)
            for (const Ring& hole : *b.holes) a -= clipped_area(hole, convex);
        return std::max(0.0, a);
    };
    if (ring_is_convex(piece)) return inside_footprint(piece);
    double total = 0;
    for (const Ring& t : triangulate(piece)) total += inside_footprint(t);
    return total;
}

namespace {

std::vector<PolygonRef> footprints_of(const std::vector<Building>& buildings) {
    std::vector<PolygonRef> out;
    out.reserve(buildings.size());
    for (const Building& b : buildings) out.push_back({&b.outer, &b.holes});
    return out;
}

}  // namespace

BuildingIndex::BuildingIndex(const std::vector<Building>& buildings, double cell)
    : BuildingIndex(footprints_of(buildings), cell) {}

BuildingIndex::BuildingIndex(std::vector<PolygonRef> polygons, double cell)
    : polygons_(std::move(polygons)), cell_(cell) {
    const std::vector<PolygonRef>& buildings = polygons_;
    boxes_.reserve(buildings.size());
    first_cell_.reserve(buildings.size());
    std::vector<std::pair<int64_t, uint32_t>> entries;  // (cell, building)
    for (uint32_t i = 0; i < buildings.size(); ++i) {
        const Box2 box = bounds_of(*buildings[i].outer);
        boxes_.push_back(box);
        first_cell_.push_back(box.empty() ? Cell{} : Cell{cell_of(box.min.x), cell_of(box.min.y)});
        if (box.empty()) continue;
        if (cells_spanned(box) > kMaxCellsPerObject) {
            large_.push_back(i);
            continue;
        }
        for (int64_t cx = cell_of(box.min.x); cx <= cell_of(box.max.x); ++cx)
            for (int64_t cy = cell_of(box.min.y); cy <= cell_of(box.max.y); ++cy) entries.push_back({grid_cell_key(cx, cy), i});
    }
    for (const PolygonRef& polygon : polygons_) {
        auto band = [&](const Ring& ring) {
            RingBands bands(ring);
            if (!bands.empty()) bands_.emplace(&ring, std::move(bands));
        };
        band(*polygon.outer);
        if (polygon.holes)
            for (const Ring& hole : *polygon.holes) band(hole);
    }
    // By cell, each cell's buildings ascending (the order the queries visit them in).
    std::sort(entries.begin(), entries.end());
    members_.reserve(entries.size());
    for (const auto& entry : entries) members_.push_back(entry.second);
    for (size_t k = 0; k < entries.size(); ++k) cell_count_ += k == 0 || entries[k].first != entries[k - 1].first;
    size_t size = 16;
    shift_ = 60;
    while (size < 2 * cell_count_) size *= 2, --shift_;
    slots_.assign(cell_count_ ? size : 0, Slot{});
    for (size_t k = 0; k < entries.size();) {
        size_t end = k + 1;
        while (end < entries.size() && entries[end].first == entries[k].first) ++end;
        size_t s = slot_hash(entries[k].first) >> shift_;
        while (slots_[s].range.begin != slots_[s].range.end) s = (s + 1) & (slots_.size() - 1);
        slots_[s] = {entries[k].first, {static_cast<uint32_t>(k), static_cast<uint32_t>(end)}};
        k = end;
    }
}

std::vector<uint32_t> BuildingIndex::near(const Box2& box) const {
    std::vector<uint32_t> out;
    for_each_near(box, [&](uint32_t i) { out.push_back(i); });
    std::sort(out.begin(), out.end());
    return out;
}

double BuildingIndex::overlap(const Ring& piece, double* max_one) const {
    double total = 0, largest = 0;
    for_each_near(bounds_of(piece), [&](uint32_t i) {
        const double a = overlap_area(piece, polygons_[i]);
        total += a;
        largest = std::max(largest, a);
    });
    if (max_one) *max_one = largest;
    return total;
}

bool BuildingIndex::in_ring(Vec2 p, const Ring& ring) const {
    const auto found = bands_.empty() ? bands_.end() : bands_.find(&ring);
    if (found == bands_.end()) return exact_point_in_ring(p, ring);
    return found->second.winding(ring, p, exact_winding_step) != 0;
}

bool BuildingIndex::contains(Vec2 p) const {
    Box2 box;
    box.extend(p);
    bool inside = false;
    for_each_near(box, [&](uint32_t i) {
        const PolygonRef& b = polygons_[i];
        if (inside || !in_ring(p, *b.outer)) return;
        bool in_hole = false;
        if (b.holes)
            for (const Ring& h : *b.holes) in_hole = in_hole || in_ring(p, h);
        inside = !in_hole;
    });
    return inside;
}

}  // namespace citygen
