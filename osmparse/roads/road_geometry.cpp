#include "osmparse/roads/road_geometry.h"

#include <algorithm>
#include <cmath>

namespace citygen {

bool intersect_lines(Vec2 p1, Vec2 d1, Vec2 p2, Vec2 d2, double& s, double& u) {
    const double den = cross(d1, d2);
    if (std::fabs(den) < 1e-9) return false;
    const Vec2 w = p2 - p1;
    s = cross(w, d2) / den;
    u = cross(w, d1) / den;
    return true;
}

double gap_angle(Vec2 a, Vec2 b) {
    double gap = std::atan2(cross(a, b), dot(a, b));
    if (gap <= 0) gap += 2 * kPi;
    return gap;
}

void push_distinct(Ring& ring, Vec2 p) {
    if (ring.empty() || length(ring.back() - p) > kSamePoint) ring.push_back(p);
}

Ring clean_ring(const Ring& ring, RingCleaning what) {
    Ring out;
    for (Vec2 p : ring) push_distinct(out, p);
    while (out.size() > 1 && length(out.front() - out.back()) <= kSamePoint) out.pop_back();
    for (bool removed = true; removed && out.size() > 3;) {
        removed = false;
        for (size_t i = 0, m = out.size(); i < m; ++i) {
            const Vec2 a = out[(i + m - 1) % m], b = out[i], c = out[(i + 1) % m];
            const bool straight = std::fabs(cross(b - a, c - b)) < kStraightTolerance * (1 + length(b - a) * length(c - b));
            if (straight && (what == RingCleaning::SpikesAndCollinear || dot(b - a, c - b) < 0)) {
                out.erase(out.begin() + static_cast<long>(i));
                removed = true;
                break;
            }
        }
    }
    return out;
}

std::array<Vec2, 9> points_beyond_quad_end(const Ring& q, bool at_from) {
    const Vec2 c1 = at_from ? q[0] : q[1], c2 = at_from ? q[3] : q[2];
    const Vec2 beyond = normalize((c1 + c2) * 0.5 - (q[0] + q[1] + q[2] + q[3]) * 0.25) * 0.01;
    std::array<Vec2, 9> points;
    for (int s = 1; s < 10; ++s) points[s - 1] = c1 + (c2 - c1) * (s / 10.0) + beyond;
    return points;
}

Ring convex_hull(std::vector<Vec2> p) {
    std::sort(p.begin(), p.end(), [](Vec2 a, Vec2 b) { return a.x != b.x ? a.x < b.x : a.y < b.y; });
    p.erase(std::unique(p.begin(), p.end()), p.end());
    if (p.size() < 3) return p;
    Ring h(2 * p.size());
    size_t k = 0;
    for (size_t i = 0; i < p.size(); ++i) {
        while (k >= 2 && cross(h[k - 1] - h[k - 2], p[i] - h[k - 2]) <= 0) --k;
        h[k++] = p[i];
    }
    for (size_t i = p.size() - 1, t = k + 1; i-- > 0;) {
        while (k >= t && cross(h[k - 1] - h[k - 2], p[i] - h[k - 2]) <= 0) --k;
        h[k++] = p[i];
    }
    h.resize(k - 1);
    return h;
}

int64_t NodeUnionFind::root(int64_t v) {
    auto it = parent_.find(v);
    if (it == parent_.end() || it->second == v) return v;
    return it->second = root(it->second);
}

bool NodeUnionFind::join(int64_t a, int64_t b) {
    a = root(a), b = root(b);
    if (a == b) return false;
    parent_[a] = parent_[b] = std::min(a, b);
    return true;
}

std::map<int64_t, std::vector<int64_t>> NodeUnionFind::sets() {
    std::map<int64_t, std::vector<int64_t>> out;
    std::vector<int64_t> nodes;
    for (const auto& [v, p] : parent_) nodes.push_back(v);  // ascending
    for (int64_t v : nodes) out[root(v)].push_back(v);
    return out;
}

}  // namespace citygen
