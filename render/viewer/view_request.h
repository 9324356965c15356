// What the viewer's page asks for: a view as render's own command-line options (the view, sky,
// light, integrator and geometry-mode groups, parsed by the CLI's parser, so every state of the
// page is a command line), plus what only the page shows: an AOV layer, bounding boxes, whether
// the camera is moving.
#pragma once

#include <string>
#include <vector>

#include "render/options.h"

namespace citygen {

enum class ViewLayer { Image, Albedo, Normal, Depth, Id };

struct ViewRequest {
    std::vector<std::string> args;  // the options, as the page sent them
    Options options;
    Job job;
    ViewLayer layer = ViewLayer::Image;
    bool building_boxes = false, road_boxes = false;
    bool moving = false;  // cheap frames until the camera stops
};

// The largest images the viewer renders live and saves (more is refused, not clamped).
constexpr long long kMaxViewerPixels = 3840LL * 2160;
constexpr long long kMaxSavedPixels = 7680LL * 4320;
constexpr size_t kMaxViewArgs = 256, kMaxViewArgLength = 256;

// Parses `args` as the viewer's options, for an image of at most `max_pixels`; throws
// citygen::Error with one line (an HTTP 400).
ViewRequest parse_view_args(const std::vector<std::string>& args, long long max_pixels);
// A request body {"args": [...], "moving": bool, "aov": "albedo", "boxes": ["buildings"]}.
ViewRequest parse_view_request(const std::string& json_body, long long max_pixels);

// The command that renders the request's view to `output`: `render SCENE ARGS -o OUTPUT`,
// each word quoted for a POSIX shell where it needs to be.
std::string command_line(const ViewRequest& request, const std::string& scene_path, const std::string& output);

// The options that decide the image apart from the camera and the image size: frames of one
// key share their exposure and need no rebuild.
std::string look_key(const ViewRequest& request);

}  // namespace citygen
