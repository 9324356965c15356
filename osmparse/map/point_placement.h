// Helpers for placing points (street lamps, trees) beside polygons: a grid of the points placed
// so far, and moving a point just outside a ring.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include "common/geometry.h"
#include "osmparse/polygons/grid_cell_key.h"

namespace citygen {

// Points already placed, bucketed for "is one within r metres" queries. Only a yes/no leaves
// it, so the hash map's order never reaches the output.
class PointGrid {
public:
    explicit PointGrid(double cell) : cell_(cell) {}
    void add(Vec2 p) { cells_[grid_cell_key(cell_of(p.x), cell_of(p.y))].push_back(p); }
    bool any_within(Vec2 p, double r) const {
        const int64_t cx = cell_of(p.x), cy = cell_of(p.y), reach = static_cast<int64_t>(std::ceil(r / cell_));
        for (int64_t x = cx - reach; x <= cx + reach; ++x)
            for (int64_t y = cy - reach; y <= cy + reach; ++y) {
                auto it = cells_.find(grid_cell_key(x, y));
                if (it == cells_.end()) continue;
                for (Vec2 q : it->second)
                    if (length(q - p) < r) return true;
            }
        return false;
    }

private:
    int64_t cell_of(double v) const { return static_cast<int64_t>(std::floor(v / cell_)); }
    double cell_;
    std::unordered_map<int64_t, std::vector<Vec2>> cells_;
};

// The point moved `margin` metres outside the nearest edge of a CCW ring (the outside is on
// the right of each edge).
inline Vec2 push_out_of(const Ring& ring, Vec2 p, double margin) {
    double best = 1e300;
    Vec2 out = p;
    for (size_t i = 0, n = ring.size(); i < n; ++i) {
        const Vec2 a = ring[i], b = ring[(i + 1) % n], ab = b - a;
        const double t = std::clamp(dot(p - a, ab) / std::max(dot(ab, ab), 1e-12), 0.0, 1.0);
        const Vec2 c = a + ab * t;
        if (length(p - c) < best) {
            best = length(p - c);
            out = c + normalize(Vec2(ab.y, -ab.x)) * margin;
        }
    }
    return out;
}

}  // namespace citygen
