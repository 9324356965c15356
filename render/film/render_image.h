// Rendering a whole image: tiles in parallel (TBB), one random stream per pixel so the result
// does not depend on the thread count (and per pixel scrambled Sobol pairs placing its samples
// and drawing their first surface's numbers, pixel_jitter.h), the light of lamp globes and lit
// panes a few pixels wide gathered per pixel (small_emitters.h), optional AOVs from the ray through each pixel
// centre.
#pragma once

#include <atomic>
#include <cstdint>
#include <memory>
#include <vector>

#include "render/camera/camera.h"
#include "render/integrator/integrator.h"

namespace citygen {

// A rectangle of pixels [x0, x1) x [y0, y1) of the full frame; empty means the whole frame.
struct PixelRegion {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    bool empty() const { return x1 <= x0 || y1 <= y0; }
    int width() const { return x1 - x0; }
    int height() const { return y1 - y0; }
};

struct RenderSettings {
    int width = 1280, height = 720;  // the full frame, also when only a region is rendered
    int spp = 16;                    // samples per pixel; with a time limit, the most passes
    // Only these pixels (the film is the crop); each pixel equals the same pixel of the full render.
    PixelRegion region;
    // When > 0: whole passes of one sample per pixel until the next pass would not end within
    // this many seconds (at least one pass). The film equals a fixed render of that many spp.
    double time_limit_seconds = 0;
    uint64_t seed = 1;
    IntegratorSettings integrator;
    bool aovs = false;   // fill depth, normal, albedo and id
    bool denoise_guides = false;  // fill the guide_* buffers (for --denoise)
    bool quiet = false;  // no progress bar
    // Lit panes a few pixels wide gathered by the film as small globes are (small_emitters.h).
    // The same expected image either way; false (--no-gather-panes) only to check that.
    bool gather_panes = true;
};

// Linear float images, row-major from the top-left pixel.
struct Film {
    int width = 0, height = 0;       // of the rendered region
    int x0 = 0, y0 = 0;              // where the film's top-left pixel lies in the full frame
    std::vector<float> rgb;          // 3 per pixel, radiance (before exposure)
    std::vector<float> raw_rgb;      // 3 per pixel, rgb before --denoise (empty unless denoised)
    // AOVs, present when RenderSettings::aovs: from the primary ray through the pixel centre.
    std::vector<float> depth;        // metres along the ray; 0 where the ray escapes
    std::vector<float> normal;       // 3 per pixel, facing the camera
    std::vector<float> albedo;       // 3 per pixel
    std::vector<float> object_kind;  // ObjectKind as a number (0: sky)
    std::vector<float> object_index; // index of the object in the scene file's list of its kind
    // Denoiser guides, present when RenderSettings::denoise_guides: albedo, normal and depth
    // averaged over 6x6 (12x12 where an edge crosses the pixel) positions in the pixel, so a
    // window narrower than a pixel still shows.
    std::vector<float> guide_albedo, guide_normal, guide_depth;
    std::vector<float> guide_direct;    // 3 per pixel, emission and haze seen directly and the
                                        // small globes and panes gathered (noise-free)
    std::vector<float> guide_variance;  // of each pixel's mean luminance, from its samples
    std::vector<float> guide_sample_direct;  // 3 per pixel, guide_direct's light along the sample rays (mean)
};

struct RenderStats {
    double seconds = 0;
    uint64_t rays = 0;
    int spp = 0;  // samples per pixel rendered (the passes reached under a time limit)
    double denoise_seconds = 0;  // the --denoise filter alone
};

// The region actually rendered: settings.region, or the whole frame when it is empty.
// Throws citygen::Error when the region does not lie inside the frame.
PixelRegion render_region(const RenderSettings& settings);

Film render_image(const PathContext& context, const Camera& camera, const RenderSettings& settings,
                  RenderStats* stats = nullptr);

struct PixelSamples;

// An image rendered a pass at a time, one sample per pixel each: every pixel keeps its random
// stream and its sum between passes, so after n passes film() equals the rgb of render_image
// with spp = n, byte for byte (--time-limit and the viewer's still frames). No AOVs or guides.
class ProgressiveRender {
public:
    // `context` and `camera` must outlive this object.
    ProgressiveRender(const PathContext& context, const Camera& camera, const RenderSettings& settings);
    ~ProgressiveRender();
    ProgressiveRender(const ProgressiveRender&) = delete;
    ProgressiveRender& operator=(const ProgressiveRender&) = delete;

    // One more sample in every pixel of the region; returns the rays it traced. Once `cancel`
    // is set the pass stops early and leaves the render unusable (the viewer drops it when a
    // new view comes).
    uint64_t add_pass(const std::atomic<bool>* cancel = nullptr);
    int spp() const { return spp_; }
    // The mean of the samples so far (zero before the first pass).
    Film film() const;

private:
    PathContext context_;
    const Camera& camera_;
    RenderSettings settings_;
    std::unique_ptr<SmallEmitters> small_emitters_;
    Film film_;  // the region; rgb filled by film()
    std::vector<PixelSamples> pixels_;
    int spp_ = 0;
};

}  // namespace citygen
