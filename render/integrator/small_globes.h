// Lamp globes that look a few pixels wide or less. A camera ray hits such a globe in a few of a
// pixel's samples or in none, so distant lamps sparkle: at 16 samples most of a night view's
// error from above is there (tests/bench/night_bench.sh), the same whichever light sampler.
// For these globes the pixel's integral is split in two (both estimates unbiased):
//   - the camera ray's own hit on the globe counts no emission (trace_path asks counts_on_film);
//   - each sample of a pixel the globe may cover aims one more ray at a point of the part of
//     the pixel inside the globe's bounding rectangle on the image, stratified over the
//     pixel's samples, and counts the globe's radiance times that part's area if the ray hits
//     the globe (so occluders, haze and fog count as for any camera ray).
// The rectangle is a few times smaller than the pixel, so the globe's light is found in most
// samples instead of in one of hundreds.
#pragma once

#include <cstdint>
#include <vector>

#include "render/camera/camera.h"
#include "render/integrator/integrator.h"
#include "render/scene/hit.h"

namespace citygen {

class SceneLights;

class SmallGlobes {
public:
    SmallGlobes() = default;  // none
    // The lamps of `lights` whose globe's bounding rectangle on `camera`'s image is at most
    // kMaxPixels wide and high.
    SmallGlobes(const SceneLights& lights, const Camera& camera);

    // Whether a camera ray's hit on this globe is left to light_in_pixel.
    bool counts_on_film(const Hit& hit) const;
    // The globes that may show in pixel (x, y), looked up once for all of its samples.
    struct InPixel {
        size_t first = 0, last = 0;  // into the covers
        bool empty() const { return first == last; }
    };
    InPixel in_pixel(int x, int y) const;
    // The light of those globes in pixel (x, y) for sample `index` of the pixel whose samples
    // are keyed by `pixel_key` (pixel_jitter.h); `rays` counts the rays traced.
    Color light_in_pixel(InPixel globes, const PathContext& context, const Camera& camera, int x, int y,
                         uint64_t pixel_key, uint32_t index, uint64_t& rays) const;

    size_t size() const { return rectangles_.size(); }
    static constexpr double kMaxPixels = 4;

private:
    struct Rectangle {
        uint32_t lamp;
        float x0, y0, x1, y1;  // on the image, in pixels
    };
    struct Cover {
        uint64_t pixel;      // y x width + x of the full frame
        uint32_t rectangle;  // into rectangles_
        bool operator<(const Cover& o) const { return pixel < o.pixel || (pixel == o.pixel && rectangle < o.rectangle); }
    };
    std::vector<uint8_t> small_;  // per lamp: its globe is one of these
    std::vector<Rectangle> rectangles_;
    std::vector<Cover> covers_;  // every pixel a rectangle overlaps, sorted
    int width_ = 0;
};

}  // namespace citygen
