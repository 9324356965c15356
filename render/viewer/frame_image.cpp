#include "render/viewer/frame_image.h"

#include <algorithm>
#include <cmath>

#include "common/ground.h"
#include "common/rng.h"
#include "render/film/image_output.h"

namespace citygen {

namespace {

unsigned char to_byte(double v) { return static_cast<unsigned char>(std::lround(std::clamp(v, 0.0, 1.0) * 255)); }

struct Box {
    Vec3 min, max;
};

// A line from a to b in pixels, clipped to the image.
void draw_line(double ax, double ay, double bx, double by, const unsigned char colour[3], int width, int height,
               std::vector<unsigned char>& rgb) {
    const int steps = static_cast<int>(std::ceil(std::max(std::fabs(bx - ax), std::fabs(by - ay))));
    if (steps > 4 * (width + height)) return;  // a corner far outside: not worth walking
    for (int s = 0; s <= steps; ++s) {
        const double t = steps ? double(s) / steps : 0;
        const int x = static_cast<int>(ax + (bx - ax) * t), y = static_cast<int>(ay + (by - ay) * t);
        if (x < 0 || y < 0 || x >= width || y >= height) continue;
        std::copy(colour, colour + 3, &rgb[3 * (static_cast<size_t>(y) * width + x)]);
    }
}

void draw_box(const Box& box, const Camera& camera, const unsigned char colour[3], int width, int height,
              std::vector<unsigned char>& rgb) {
    Vec3 corner[8];
    for (int i = 0; i < 8; ++i)
        corner[i] = {i & 1 ? box.max.x : box.min.x, i & 2 ? box.max.y : box.min.y, i & 4 ? box.max.z : box.min.z};
    double px[8], py[8];
    for (int i = 0; i < 8; ++i)
        if (!camera.project(corner[i], &px[i], &py[i])) return;  // partly behind the camera: left out
    for (int i = 0; i < 8; ++i)
        for (int bit : {1, 2, 4})
            if (!(i & bit)) draw_line(px[i], py[i], px[i | bit], py[i | bit], colour, width, height, rgb);
}

}  // namespace

std::vector<unsigned char> tone_mapped_rgb8(const Film& film, double exposure) {
    std::vector<unsigned char> rgb(film.rgb.size());
    for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = to_byte(tone_map(film.rgb[i], exposure));
    return rgb;
}

std::vector<unsigned char> layer_rgb8(const Film& film, ViewLayer layer) {
    const size_t pixels = static_cast<size_t>(film.width) * film.height;
    std::vector<unsigned char> rgb(3 * pixels, 0);
    if (film.depth.size() != pixels) return rgb;
    double far = 1;
    for (float d : film.depth) far = std::max(far, static_cast<double>(d));
    for (size_t i = 0; i < pixels; ++i) {
        unsigned char* p = &rgb[3 * i];
        switch (layer) {
            case ViewLayer::Albedo:
                for (int c = 0; c < 3; ++c) p[c] = to_byte(std::pow(film.albedo[3 * i + c], 1 / 2.2));
                break;
            case ViewLayer::Normal:
                for (int c = 0; c < 3; ++c) p[c] = to_byte(0.5 + 0.5 * film.normal[3 * i + c]);
                break;
            case ViewLayer::Depth: {
                const double d = film.depth[i];
                const unsigned char v = d > 0 ? to_byte(1 - std::log1p(d) / std::log1p(far)) : 0;
                p[0] = p[1] = p[2] = v;
                break;
            }
            case ViewLayer::Id: {
                if (film.object_kind[i] == 0) break;
                const uint64_t h = hash_keys(static_cast<uint64_t>(film.object_kind[i]),
                                             static_cast<uint64_t>(film.object_index[i]));
                for (int c = 0; c < 3; ++c) p[c] = static_cast<unsigned char>(64 + ((h >> (8 * c)) & 0xff) * 3 / 4);
                break;
            }
            case ViewLayer::Image:
                break;
        }
    }
    return rgb;
}

void draw_boxes(const Scene& scene, const Camera& view, bool buildings, bool roads, int width, int height,
                std::vector<unsigned char>& rgb) {
    const Camera camera = view.resized(width, height);
    static const unsigned char kBuildingColour[3] = {255, 214, 0}, kRoadColour[3] = {0, 220, 255};
    if (buildings)
        for (const Building& b : scene.buildings) {
            if (!has_volume(b)) continue;
            Box box{{1e30, 1e30, 0}, {-1e30, -1e30, 0}};
            for (Vec2 p : b.outer)
                box.min = {std::min(box.min.x, p.x), std::min(box.min.y, p.y), 0},
                box.max = {std::max(box.max.x, p.x), std::max(box.max.y, p.y), 0};
            const double base = building_base(scene, b);
            box.min.z = base + b.min_height;
            box.max.z = base + b.height;
            draw_box(box, camera, kBuildingColour, width, height, rgb);
        }
    if (roads)
        for (const RoadEdge& r : scene.roads) {
            if (r.quad.empty()) continue;
            Box box{{1e30, 1e30, 1e30}, {-1e30, -1e30, -1e30}};
            for (Vec2 p : r.quad) {
                const double z = ground_height(scene, p.x, p.y);
                box.min = {std::min(box.min.x, p.x), std::min(box.min.y, p.y), std::min(box.min.z, z)};
                box.max = {std::max(box.max.x, p.x), std::max(box.max.y, p.y), std::max(box.max.z, z + 0.5)};
            }
            draw_box(box, camera, kRoadColour, width, height, rgb);
        }
}

}  // namespace citygen
