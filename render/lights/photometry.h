// Photometric units for the renderer's radiance values, and colours of light sources.
//
// The renderer's radiance unit is the one the daylight sky was calibrated in (sky.cpp: a clear
// zenith of 1 kcd/m^2 is 0.06): one unit of radiance is 1000 / 0.06 = 16,667 cd/m^2 of
// luminance (and one unit of irradiance 16,667 lux). Lamps given in lumens and windows in
// cd/m^2 are converted with it, so sun, sky, lamps and windows keep their real proportions.
#pragma once

#include "render/materials/materials.h"

namespace citygen {

constexpr double kNitsPerRadianceUnit = 1000.0 / 0.06;

// Linear sRGB colour of a black body at `kelvin` (Planckian locus after Kim et al. 2002, valid
// 1667..25000 K), scaled to luminance 1.
Color blackbody_color(double kelvin);

}  // namespace citygen
