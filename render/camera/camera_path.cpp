#include "render/camera/camera_path.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "common/error.h"
#include "common/scene_limits.h"

namespace citygen {

namespace {


// Splits a CSV line into numbers; false unless it is exactly `count` finite numbers.
bool parse_numbers(const std::string& line, size_t count, std::vector<double>& out) {
    out.clear();
    std::stringstream in(line);
    for (std::string field; std::getline(in, field, ',');) {
        const size_t begin = field.find_first_not_of(" \t\r");
        const size_t end = field.find_last_not_of(" \t\r");
        if (begin == std::string::npos) return false;
        const std::string text = field.substr(begin, end - begin + 1);
        char* stop = nullptr;
        const double value = std::strtod(text.c_str(), &stop);
        if (stop != text.c_str() + text.size() || !std::isfinite(value)) return false;
        out.push_back(value);
    }
    return out.size() == count;
}

// Centripetal Catmull-Rom (alpha 1/2) between p1 and p2 at u in [0, 1], in the Barry-Goldman
// pyramid form. Knot spacing is the square root of the chord length, which avoids cusps and
// self-intersections; a tiny floor keeps coincident keys (a camera at rest) well defined.
Vec3 centripetal_catmull_rom(Vec3 p0, Vec3 p1, Vec3 p2, Vec3 p3, double u) {
    auto spacing = [](Vec3 a, Vec3 b) { return std::max(std::sqrt(length(b - a)), 1e-9); };
    const double k0 = 0, k1 = k0 + spacing(p0, p1), k2 = k1 + spacing(p1, p2), k3 = k2 + spacing(p2, p3);
    const double t = k1 + u * (k2 - k1);
    auto lerp = [](Vec3 a, Vec3 b, double ka, double kb, double t) {
        return a * ((kb - t) / (kb - ka)) + b * ((t - ka) / (kb - ka));
    };
    const Vec3 a1 = lerp(p0, p1, k0, k1, t), a2 = lerp(p1, p2, k1, k2, t), a3 = lerp(p2, p3, k2, k3, t);
    const Vec3 b1 = lerp(a1, a2, k0, k2, t), b2 = lerp(a2, a3, k1, k3, t);
    return lerp(b1, b2, k1, k2, t);
}

}  // namespace

CameraPath parse_camera_path(const std::string& text, const std::string& name) {
    CameraPath path;
    std::stringstream in(text);
    int line_number = 0;
    std::vector<double> v;
    for (std::string line; std::getline(in, line);) {
        ++line_number;
        const size_t first = line.find_first_not_of(" \t\r");
        if (first == std::string::npos || line[first] == '#') continue;
        if (path.keys.empty() && line.compare(first, 4, "time") == 0) continue;  // column names
        const std::string where = name + ":" + std::to_string(line_number) + ": ";
        if (!parse_numbers(line, 8, v))
            throw Error(where + "expected time,x,y,z,look_x,look_y,look_z,fov (8 numbers)");
        CameraKey key{v[0], {v[1], v[2], v[3]}, {v[4], v[5], v[6]}, v[7]};
        if (!path.keys.empty() && key.time <= path.keys.back().time)
            throw Error(where + "times must increase from key to key");
        if (key.fov < 1 || key.fov > 170) throw Error(where + "fov must be between 1 and 170 degrees");
        if (length(key.look_at - key.position) < 1e-6) throw Error(where + "camera and look-at coincide");
        if (!(key.time >= 0 && key.time <= kMaxPathSeconds))
            throw Error(where + "time must be between 0 and " + std::to_string(static_cast<long>(kMaxPathSeconds)) + " s");
        for (double c : {key.position.x, key.position.y, key.position.z, key.look_at.x, key.look_at.y, key.look_at.z})
            if (std::fabs(c) > kMaxCoordinate)  // as for --camera: beyond, Embree's arithmetic overflows
                throw Error(where + "a coordinate is more than " + std::to_string(static_cast<long>(kMaxCoordinate)) +
                            " m from the scene origin");
        path.keys.push_back(key);
    }
    if (path.keys.size() < 2) throw Error(name + ": a camera path needs at least two keyframes");
    return path;
}

CameraPath read_camera_path(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw Error(path + ": cannot open camera path");
    std::stringstream text;
    text << in.rdbuf();
    return parse_camera_path(text.str(), path);
}

CameraKey camera_path_at(const CameraPath& path, double time) {
    const std::vector<CameraKey>& keys = path.keys;
    if (time <= keys.front().time) return keys.front();
    if (time >= keys.back().time) return keys.back();
    // The segment [i, i + 1] holding `time`; a key's own time returns the key itself.
    const size_t i = static_cast<size_t>(
        std::upper_bound(keys.begin(), keys.end(), time, [](double t, const CameraKey& k) { return t < k.time; }) -
        keys.begin() - 1);
    if (keys[i].time == time) return keys[i];
    const double u = (time - keys[i].time) / (keys[i + 1].time - keys[i].time);
    auto point = [&](long j, Vec3 CameraKey::*member) -> Vec3 {
        // Beyond the ends: the end key reflected through its neighbour.
        const long n = static_cast<long>(keys.size());
        if (j < 0) return keys[0].*member * 2 - keys[1].*member;
        if (j >= n) return keys[n - 1].*member * 2 - keys[n - 2].*member;
        return keys[j].*member;
    };
    const long s = static_cast<long>(i);
    CameraKey key;
    key.time = time;
    key.position = centripetal_catmull_rom(point(s - 1, &CameraKey::position), point(s, &CameraKey::position),
                                           point(s + 1, &CameraKey::position), point(s + 2, &CameraKey::position), u);
    key.look_at = centripetal_catmull_rom(point(s - 1, &CameraKey::look_at), point(s, &CameraKey::look_at),
                                          point(s + 1, &CameraKey::look_at), point(s + 2, &CameraKey::look_at), u);
    key.fov = keys[i].fov + u * (keys[i + 1].fov - keys[i].fov);
    return key;
}

CameraKey orbit_at(Vec3 start, Vec3 centre, double fov, double seconds, double time) {
    const double radius = std::hypot(start.x - centre.x, start.y - centre.y);
    const double angle = std::atan2(start.y - centre.y, start.x - centre.x) + 2 * kPi * time / seconds;
    CameraKey key;
    key.time = time;
    key.position = {centre.x + radius * std::cos(angle), centre.y + radius * std::sin(angle), start.z};
    key.look_at = centre;
    key.fov = fov;
    return key;
}

FrameRange parse_frame_range(const std::string& text) {
    const std::string message = "--frames: expected A-B or N with 0 <= A <= B, got '" + text + "'";
    FrameRange range;
    char dash = 0;
    std::stringstream in(text);
    if (!(in >> range.first)) throw Error(message);
    range.last = range.first;
    if (in >> dash) {
        if (dash != '-' || !(in >> range.last)) throw Error(message);
    }
    if (!(in >> std::ws).eof() || range.first < 0 || range.last < range.first) throw Error(message);
    return range;
}

FrameRange frames_within(double start, double end, double fps) {
    // A small tolerance so that a key at exactly n / fps seconds counts despite rounding.
    const double eps = 1e-9;
    return {static_cast<int>(std::ceil(start * fps - eps)), static_cast<int>(std::floor(end * fps + eps))};
}

std::string frame_file_name(const std::string& pattern, int frame) {
    std::string out;
    int numbers = 0;
    for (size_t i = 0; i < pattern.size(); ++i) {
        if (pattern[i] != '%') {
            out += pattern[i];
            continue;
        }
        if (i + 1 < pattern.size() && pattern[i + 1] == '%') {
            out += '%';
            ++i;
            continue;
        }
        size_t j = i + 1;
        int width = 0;
        const bool zero = j < pattern.size() && pattern[j] == '0';
        while (j < pattern.size() && std::isdigit(static_cast<unsigned char>(pattern[j])) && width < 100)
            width = 10 * width + (pattern[j++] - '0');
        if (j >= pattern.size() || pattern[j] != 'd')
            throw Error(pattern + ": only %d or %0Nd (and %%) may appear in an output pattern");
        std::string number = std::to_string(frame);
        if (number.size() < static_cast<size_t>(width)) number.insert(0, width - number.size(), zero ? '0' : ' ');
        out += number;
        ++numbers;
        i = j;
    }
    if (numbers != 1)
        throw Error(pattern + ": an animation's output needs one frame number in its name, e.g. out_%04d.png");
    return out;
}

}  // namespace citygen
