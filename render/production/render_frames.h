// What `render` does with a view once the scene is built: one still (maybe a region of the frame,
// maybe under a time limit, maybe denoised) or the frames of an animation, each written on its own.
// Every frame and every region is a pure function of (scene, options, seed, frame number).
#pragma once

#include <functional>
#include <string>

#include "render/camera/camera_path.h"
#include "render/film/denoise.h"
#include "render/film/render_image.h"

namespace citygen {

// Renders settings.region of the view. With `denoise`, the region is rendered with a margin of
// denoise_margin() pixels (within the frame), filtered and cropped, so a denoised tile equals the
// same pixels of the denoised full frame. AOVs stay on the film only when settings.aovs asks.
Film render_view(const PathContext& context, const Camera& camera, const RenderSettings& settings, bool denoise,
                 double exposure, RenderStats* stats = nullptr);

struct Animation {
    std::function<CameraKey(double seconds)> view;  // camera at a time
    FrameRange frames;
    double fps = 24;
    std::string output_pattern;  // out_%04d.png
};

// Renders and writes each frame (frame n at time n / fps) to its own file, exposed with
// exposure_for(its camera); unless quiet, one line per frame on stderr: frame k of n, its
// seconds and the ETA of the whole run.
void render_animation(const PathContext& context, const Animation& animation, const RenderSettings& settings,
                      bool denoise, const std::function<double(const Camera&)>& exposure_for);

}  // namespace citygen
