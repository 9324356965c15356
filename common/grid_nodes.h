// Walking a grid's nodes: those inside a polygon, and those near a segment. The DEM grid and the
// scene's height field share the layout (node (i, j) at origin + (i * cell, j * cell)), so both
// are walked through GridLayout.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "common/geometry.h"

namespace citygen {

struct GridLayout {
    Vec2 origin;
    double cell = 0;
    uint32_t nx = 0, ny = 0;

    size_t index(uint32_t i, uint32_t j) const { return static_cast<size_t>(j) * nx + i; }
    Vec2 node(uint32_t i, uint32_t j) const { return {origin.x + i * cell, origin.y + j * cell}; }
};

// Calls visit(i, j) for each node inside the rings (even-odd: holes given among them are left out).
template <class Visit>
void for_each_node_inside(const GridLayout& g, const std::vector<const Ring*>& rings, Visit&& visit) {
    Box2 box;
    for (const Ring* ring : rings)
        for (Vec2 p : *ring) box.extend(p);
    if (box.empty()) return;
    const double j0 = std::max(0.0, std::ceil((box.min.y - g.origin.y) / g.cell));
    const double j1 = std::min(g.ny - 1.0, std::floor((box.max.y - g.origin.y) / g.cell));
    std::vector<double> crossings;
    // Row by row: the nodes between pairs of boundary crossings.
    for (double jj = j0; jj <= j1; ++jj) {
        const auto j = static_cast<uint32_t>(jj);
        const double y = g.origin.y + j * g.cell;
        crossings.clear();
        for (const Ring* ring : rings)
            for (size_t a = 0; a < ring->size(); ++a) {
                const Vec2 p = (*ring)[a], q = (*ring)[(a + 1) % ring->size()];
                if ((p.y <= y) != (q.y <= y)) crossings.push_back(p.x + (y - p.y) / (q.y - p.y) * (q.x - p.x));
            }
        std::sort(crossings.begin(), crossings.end());
        for (size_t m = 0; m + 1 < crossings.size(); m += 2) {
            const double first = std::ceil((crossings[m] - g.origin.x) / g.cell);
            const double last = std::floor((crossings[m + 1] - g.origin.x) / g.cell);
            for (double i = std::max(first, 0.0); i <= std::min(last, g.nx - 1.0); ++i)
                visit(static_cast<uint32_t>(i), j);
        }
    }
}

// Calls visit(i, j, distance, t) for each node within `reach` of the segment a->b: its distance
// to the segment and the parameter in [0, 1] of the segment's point nearest to it.
template <class Visit>
void for_each_node_near(const GridLayout& g, Vec2 a, Vec2 b, double reach, Visit&& visit) {
    const double i0 = std::max(0.0, std::ceil((std::min(a.x, b.x) - reach - g.origin.x) / g.cell));
    const double i1 = std::min(g.nx - 1.0, std::floor((std::max(a.x, b.x) + reach - g.origin.x) / g.cell));
    const double j0 = std::max(0.0, std::ceil((std::min(a.y, b.y) - reach - g.origin.y) / g.cell));
    const double j1 = std::min(g.ny - 1.0, std::floor((std::max(a.y, b.y) + reach - g.origin.y) / g.cell));
    const Vec2 d = b - a;
    const double length2 = dot(d, d);
    for (double jj = j0; jj <= j1; ++jj)
        for (double ii = i0; ii <= i1; ++ii) {
            const auto i = static_cast<uint32_t>(ii), j = static_cast<uint32_t>(jj);
            const Vec2 p = g.node(i, j);
            const double t = length2 > 0 ? std::clamp(dot(p - a, d) / length2, 0.0, 1.0) : 0.0;
            const double distance = length(p - (a + d * t));
            if (distance <= reach) visit(i, j, distance, t);
        }
}

}  // namespace citygen
