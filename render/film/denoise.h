// An edge-avoiding à-trous wavelet filter (Dammertz, Sewtz, Hanika, Lensch: "Edge-Avoiding
// À-Trous Wavelet Transform for fast Global Illumination Filtering", HPG 2010), guided by the
// noise-free AOVs of the ray through each pixel centre: normal, depth, albedo and object id.
//
// Each level blurs with the B3-spline kernel (1/16, 1/4, 3/8, 1/4, 1/16) whose taps lie 2^level
// pixels apart, and weights every tap by how alike the two pixels are: luminance, measured in
// units of the pixel's own noise (the variance of its samples, filtered along, as in SVGF by
// Schied et al. 2017; the tolerance halves with each level, as the paper's colour tolerance), normal,
// relative depth and albedo; pixels of another object (or the sky) get no weight at all. The
// filter works on colour minus the direct light (emitters, haze, the sun's light with hard
// shadows) along the pixel's own sample rays (film.guide_sample_direct, so where the samples
// fell does not count as noise), divided by albedo; the direct light of film.guide_direct (the
// same over a fixed grid in the pixel) goes back unfiltered, so texture, lamps, lit windows and
// shadow edges are kept. Every pixel is computed alone from the previous level, so the result
// does not depend on the thread count.
#pragma once

#include "render/film/render_image.h"

namespace citygen {

struct DenoiseSettings {
    int levels = 4;            // taps 1, 2, 4, 8 pixels apart
    double sigma_luminance = 6;  // luminance difference, in standard deviations of the pixel's noise, halving per level
    double sigma_normal = 0.7; // length of the difference of unit normals
    double sigma_depth = 0.03; // depth difference relative to depth, per pixel of tap distance
    double sigma_albedo = 0.2; // albedo difference
};

// How far (in pixels, each way) a filtered pixel sees: a region rendered this much larger and
// then cropped filters exactly like the full frame.
int denoise_margin(const DenoiseSettings& settings);

// Filters film.rgb in place (it needs the film's AOVs) and keeps the unfiltered radiance in
// film.raw_rgb. `exposure` scales radiance to display values for the colour weight.
void denoise(Film& film, double exposure, const DenoiseSettings& settings = {});

}  // namespace citygen
