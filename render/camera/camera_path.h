// Camera paths for animations: keyframes read from a small CSV file and interpolated with a
// centripetal Catmull-Rom spline, an orbit around the scene for people who have no path, and
// the frame numbers and file names of an animation.
//
// The CSV file: one keyframe per line, `time,x,y,z,look_x,look_y,look_z,fov` (seconds, scene
// metres, vertical field of view in degrees), times strictly increasing; blank lines and lines
// starting with '#' are skipped, and so is a first line naming the columns (starting "time").
#pragma once

#include <string>
#include <vector>

#include "common/scene.h"

namespace citygen {

// The longest camera path or orbit, seconds: frame numbers (time x fps, fps <= 1000) stay
// far inside int.
constexpr double kMaxPathSeconds = 1e6;

struct CameraKey {
    double time = 0;  // seconds
    Vec3 position, look_at;
    double fov = 50;  // vertical, degrees
};

struct CameraPath {
    std::vector<CameraKey> keys;  // at least two, times strictly increasing
};

// Throws citygen::Error naming the file and line for anything malformed.
CameraPath read_camera_path(const std::string& path);
CameraPath parse_camera_path(const std::string& text, const std::string& name);

// The view at `time` (clamped to the path's span): position and look-at on centripetal
// Catmull-Rom splines through the keys (ends extended by reflection), fov linear between keys.
// At a key's time it is that key exactly. The direction of travel is continuous across keys;
// the speed within a segment follows the segment's duration.
CameraKey camera_path_at(const CameraPath& path, double time);

// One full turn in `seconds` around `centre` at the horizontal distance and height of `start`,
// looking at `centre`, starting at `start`.
CameraKey orbit_at(Vec3 start, Vec3 centre, double fov, double seconds, double time);

// Frames [first, last] of an animation; frame n shows time n / fps.
struct FrameRange {
    int first = 0, last = 0;
    int count() const { return last - first + 1; }
};

// "A-B" or "N"; throws citygen::Error unless 0 <= A <= B.
FrameRange parse_frame_range(const std::string& text);

// The frames whose times lie within [start, end] seconds at `fps`.
FrameRange frames_within(double start, double end, double fps);

// `pattern` with its one %d or %0Nd replaced by `frame` (printf's rules; "%%" is a '%').
// Throws citygen::Error unless the pattern has exactly one frame number.
std::string frame_file_name(const std::string& pattern, int frame);

}  // namespace citygen
