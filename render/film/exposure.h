// Exposure for the displayed image: automatic from the film's own luminance, or a photographic
// exposure value (--exposure EV, at ISO 100) set by hand. Radiance is photometric (one unit is
// kNitsPerRadianceUnit cd/m^2), so EVs mean what they mean on a camera: ~15 for a sunny
// street, ~9 at dusk, ~3 under street lamps. The EXR output stays linear and unscaled.
#pragma once

#include "render/film/render_image.h"

namespace citygen {

// Multiplier on radiance before the tone curve for an exposure value at ISO 100 (saturation-
// based: the luminance that just saturates is 1.2 x 2^EV cd/m^2, then rescaled for the
// filmic curve, which reaches white near 10).
double exposure_from_ev(double ev100);
double ev_from_exposure(double exposure);

// Automatic exposure: the film's log-average luminance is brought to a key that is mid-grey
// (0.18) for bright scenes and lower for dark ones (as Krawczyk et al. 2005 do), so a night
// stays a night and a day is not washed out. Deterministic: a function of the pixels alone.
double auto_exposure(const Film& film);

// Automatic exposure of a view, metered on a small image of the whole frame (at most 160 pixels
// wide, 4 spp, the render's seed) before the render: every tile of a frame and every region
// gets the same exposure, so tiles still merge into the full image byte for byte.
double metered_exposure(const PathContext& context, const Camera& camera, const RenderSettings& settings);

}  // namespace citygen
