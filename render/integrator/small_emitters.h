// Lamp globes and lit window panes that look a few pixels wide or less. A camera ray hits such
// an emitter in a few of a pixel's samples or in none, so distant lamps and windows sparkle: at
// 16 samples most of a night view's error from above is there (tests/bench/night_bench.sh), the
// same whichever light sampler. For these emitters the pixel's integral is split in two (both
// estimates unbiased):
//   - the camera ray's own hit on the emitter counts no emission (trace_path asks counts_on_film);
//   - each sample of a pixel the emitter may cover aims one more ray at a point of the part of
//     the pixel inside the emitter's bounding rectangle on the image, stratified over the
//     pixel's samples, and counts the emitter's radiance there times that part's area if the
//     ray hits the emitter's front (so occluders, haze and fog count as for any camera ray).
// The rectangle is a few times smaller than the pixel, so the light is found in most samples
// instead of in one of hundreds. A pane's rectangle bounds the part of it the camera sees
// through its opening (the reveals hide the rest from an oblique view), so few rays miss.
#pragma once

#include <cstdint>
#include <deque>
#include <vector>

#include "render/camera/camera.h"
#include "render/integrator/integrator.h"
#include "render/scene/hit.h"

namespace citygen {

class SceneLights;

class SmallEmitters {
public:
    SmallEmitters() = default;  // none
    // The lamps of `lights` whose globe's bounding rectangle on `camera`'s image is at most
    // kMaxPixels wide and high, and (with `panes`) the lit panes whose visible part's is; those
    // off the image are left out (no camera ray meets them).
    SmallEmitters(const SceneLights& lights, const Camera& camera, bool panes = true);

    // Whether a camera ray's hit on this emitter is left to light_in_pixel.
    bool counts_on_film(const Hit& hit) const;
    // The emitters that may show in pixel (x, y), looked up once for all of its samples.
    struct InPixel {
        size_t first = 0, last = 0;  // into the covers
        bool empty() const { return first == last; }
    };
    InPixel in_pixel(int x, int y) const;
    // The light of those emitters in pixel (x, y) for sample `index` of the pixel whose samples
    // are keyed by `pixel_key` (pixel_jitter.h); `rays` counts the rays traced.
    Color light_in_pixel(InPixel emitters, const PathContext& context, const Camera& camera, int x, int y,
                         uint64_t pixel_key, uint32_t index, uint64_t& rays) const;

    size_t size() const { return rectangles_.size(); }  // on the image
    size_t pane_count() const { return panes_.size(); }  // on the image
    static constexpr double kMaxPixels = 4;
    // Rays a sample aims at a pixel's emitters: beyond, it picks this many in proportion to the
    // area they cover. 8: Kaiserslautern's elevated view at 1920x1080 has 3 pixels with more
    // (its 8x8 metropolis has 30,106, up to 2,172 emitters each).
    static constexpr int kMaxRaysPerSample = 8;

private:
    struct Rectangle {
        uint32_t object;      // the lamp, or the pane's building
        uint32_t wall, cell;  // the pane's, as its Hit carries them; cell 0: a lamp globe
        float x0, y0, x1, y1;  // on the image, in pixels
        bool matches(const Hit& hit) const;
    };
    struct PaneId {
        uint32_t building, wall, cell;
        bool operator<(const PaneId& o) const {
            return building != o.building ? building < o.building : wall != o.wall ? wall < o.wall : cell < o.cell;
        }
    };
    struct Cover {
        uint64_t pixel;      // y x width + x of the full frame
        uint32_t rectangle;  // into rectangles_
        bool operator<(const Cover& o) const { return pixel < o.pixel || (pixel == o.pixel && rectangle < o.rectangle); }
    };
    // Whether the rectangle [x0, x1] x [y0, y1] is small and on the image.
    static bool fits(const Camera& camera, double x0, double y0, double x1, double y1);
    // Keeps the rectangle if it fits (true).
    bool add(const Camera& camera, Rectangle r, double x0, double y0, double x1, double y1);

    std::vector<uint8_t> small_;   // per lamp: its globe is one of these
    std::vector<PaneId> panes_;    // the gathered panes, sorted
    // Deques: seen from above a metropolis has millions, and they grow without being copied.
    std::deque<Rectangle> rectangles_;
    std::deque<Cover> covers_;  // every pixel a rectangle overlaps, sorted
    int width_ = 0;
};

}  // namespace citygen
