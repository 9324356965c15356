// A long ring's edges sorted into bands of y, for point-in-ring tests against rings of thousands
// of vertices (the sea, a forest, a lake). An edge adds to a point's winding number only if the
// point's y lies within the edge's, so the edges of the point's band give the same number as all
// of them: the same answer, with the same per-edge test, from a few edges.
#pragma once

#include <cstdint>
#include <vector>

#include "common/geometry.h"

namespace citygen {

class RingBands {
public:
    // Rings shorter than this are tested edge by edge: banding would not pay.
    static constexpr size_t kMinVertices = 256;

    // No bands (empty()) for a short or flat ring, or one whose edges each cross many bands (a
    // zigzag across the whole ring would make the bands quadratic in its size).
    explicit RingBands(const Ring& ring);
    bool empty() const { return first_.empty(); }

    // The sum of step(a, b, p) over the edges a -> b of `ring` (the one the bands were made of)
    // that can count for p: those of p's band, or all of them without bands.
    template <typename Step>
    int winding(const Ring& ring, Vec2 p, Step step) const {
        const size_t n = ring.size();
        int sum = 0;
        if (empty()) {
            for (size_t i = 0; i < n; ++i) sum += step(ring[i], ring[i + 1 == n ? 0 : i + 1], p);
            return sum;
        }
        const size_t band = band_of(p.y);
        for (uint32_t e = first_[band]; e < first_[band + 1]; ++e) {
            const uint32_t i = edges_[e];
            sum += step(ring[i], ring[i + 1 == n ? 0 : i + 1], p);
        }
        return sum;
    }

private:
    size_t band_of(double y) const;  // clamped, and monotonic in y: each step rounds monotonically
    double y0_ = 0, height_ = 1;     // band k holds y in [y0 + k height, y0 + (k + 1) height)
    std::vector<uint32_t> first_;    // band k's edges are edges_[first_[k] .. first_[k + 1])
    std::vector<uint32_t> edges_;    // edge i: ring[i] -> ring[i + 1]
};

}  // namespace citygen
