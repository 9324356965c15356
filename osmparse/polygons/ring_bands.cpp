#include "osmparse/polygons/ring_bands.h"

#include <algorithm>
#include <cmath>

namespace citygen {

RingBands::RingBands(const Ring& ring) {
    const size_t n = ring.size();
    if (n < kMinVertices) return;
    const Box2 box = bounds_of(ring);
    if (!(box.max.y > box.min.y)) return;
    const size_t count = n / 8;  // about eight edges a band where they are spread evenly
    y0_ = box.min.y;
    height_ = (box.max.y - box.min.y) / static_cast<double>(count);
    first_.assign(count + 1, 0);
    // Each edge goes in every band its y range meets: counted first, then placed.
    size_t entries = 0;
    for (size_t i = 0; i < n; ++i) {
        const Vec2 a = ring[i], b = ring[i + 1 == n ? 0 : i + 1];
        const size_t lo = band_of(std::min(a.y, b.y)), hi = band_of(std::max(a.y, b.y));
        entries += hi - lo + 1;
        if (entries > 16 * n) {
            first_.clear();
            return;
        }
        for (size_t k = lo; k <= hi; ++k) ++first_[k + 1];
    }
    for (size_t k = 0; k < count; ++k) first_[k + 1] += first_[k];
    edges_.resize(entries);
    std::vector<uint32_t> next(first_.begin(), first_.end() - 1);
    for (size_t i = 0; i < n; ++i) {
        const Vec2 a = ring[i], b = ring[i + 1 == n ? 0 : i + 1];
        for (size_t k = band_of(std::min(a.y, b.y)), hi = band_of(std::max(a.y, b.y)); k <= hi; ++k)
            edges_[next[k]++] = static_cast<uint32_t>(i);
    }
}

size_t RingBands::band_of(double y) const {
    const double k = std::floor((y - y0_) / height_);
    return static_cast<size_t>(std::clamp(k, 0.0, static_cast<double>(first_.size() - 2)));
}

}  // namespace citygen
