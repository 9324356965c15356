// A weighted first-order regression filter (after Moon, Carr and Yoon: "Adaptive Rendering based
// on Weighted Local Regression", TOG 2014, and Bitterli et al.: "Nonlinearly Weighted
// First-order Regression for Denoising Monte Carlo Renderings", EGSR 2016), guided by what the
// film knows without noise about each pixel: albedo, normal, depth and direct light, averaged
// over the pixel.
//
// For every pixel the filter fits, over a window of neighbours, the light as a linear function
// of how the neighbours' guides and image positions differ from the pixel's, and keeps the fit's
// value at the pixel itself. A pixel that mixes a roof, a wall and a street (a building a few
// pixels wide) has no neighbour with its guides, but it lies between neighbours that show each
// part; an average of alike pixels, as the earlier edge-avoiding à-trous filter was, leaves it
// as noisy as it came. Neighbours weigh by distance, by how alike their guides are, and by how
// alike the mean luminance of their 3x3 patch is, in units of the pixel's own noise (from the
// variance of its samples): a shadow or lamp pool that no guide knows stays, and a firefly is
// not spread. Only the sky is a hard edge.
//
// The filter works on colour minus the direct light (emitters, haze, the sun's light with hard
// shadows) along the pixel's own sample rays (film.guide_sample_direct, so where the samples
// fell does not count as noise), divided by albedo; the direct light of film.guide_direct (the
// same over a fixed grid in the pixel) goes back unfiltered, so texture, lamps, lit windows and
// shadow edges are kept. Every pixel is computed alone, so the result does not depend on the
// thread count.
#pragma once

#include "render/film/render_image.h"

namespace citygen {

struct DenoiseSettings {
    int radius = 9;               // the window: (2 radius + 1)^2 pixels, weighted by a Gaussian of sigma radius / 2
    double sigma_luminance = 2;   // 3x3 patch luminance difference, in standard deviations of the pixel's noise
    double sigma_normal = 1.0;    // length of the difference of the pixels' mean normals
    double sigma_depth = 0.03;    // depth difference relative to depth, per pixel of distance
    double sigma_albedo = 0.2;    // albedo difference
    double ridge = 1e-4;          // pull of the fit's slopes towards zero, relative to the window's weight
};

// How far (in pixels, each way) a filtered pixel sees: a region rendered this much larger and
// then cropped filters exactly like the full frame.
int denoise_margin(const DenoiseSettings& settings);

// Filters film.rgb in place (it needs the film's AOVs) and keeps the unfiltered radiance in
// film.raw_rgb. `exposure` scales radiance to display values.
void denoise(Film& film, double exposure, const DenoiseSettings& settings = {});

}  // namespace citygen
