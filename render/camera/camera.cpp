#include "render/camera/camera.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "render/geometry/ground.h"

namespace citygen {

Camera Camera::look_at(Vec3 position, Vec3 target, double vertical_fov_deg, int width, int height) {
    Camera c;
    c.position_ = position;
    c.forward_ = normalize(target - position);
    Vec3 world_up{0, 0, 1};
    if (std::fabs(dot(c.forward_, world_up)) > 0.999) world_up = {0, 1, 0};  // looking straight down
    c.right_ = normalize(cross(c.forward_, world_up));
    c.up_ = cross(c.right_, c.forward_);
    c.tan_half_fov_ = std::tan(0.5 * vertical_fov_deg * kPi / 180);
    c.width_ = width;
    c.height_ = height;
    c.aspect_ = static_cast<double>(width) / height;
    return c;
}

Camera Camera::resized(int width, int height) const {
    Camera c = *this;
    c.width_ = width;
    c.height_ = height;
    c.aspect_ = static_cast<double>(width) / height;
    return c;
}

Ray Camera::generate_ray(double px, double py) const {
    const double sx = (2 * px / width_ - 1) * tan_half_fov_ * aspect_;
    const double sy = (1 - 2 * py / height_) * tan_half_fov_;
    Ray ray;
    ray.origin = position_;
    ray.direction = normalize(forward_ + right_ * sx + up_ * sy);
    return ray;
}

bool Camera::project(Vec3 p, double* px, double* py) const {
    const Vec3 d = p - position_;
    const double z = dot(d, forward_);
    if (!(z > 0)) return false;
    *px = (dot(d, right_) / (z * tan_half_fov_ * aspect_) + 1) * 0.5 * width_;
    *py = (1 - dot(d, up_) / (z * tan_half_fov_)) * 0.5 * height_;
    return true;
}

namespace {

// What the automatic view frames: the buildings (roads may run far out of town); failing that
// the roads, then the header bounds. The corners are every building corner, foot and top (road
// corners when there are no buildings): a diagonal town leaves its bounding box's corners empty.
struct TownExtent {
    Box2 box;
    double top = 0, radius = 0;
    std::vector<Vec3> corners;
};

// The square window of kDensestWindow metres (on a grid of kDensestCell) holding the most
// building floor area, by each building's first corner; everything when the buildings fit in
// one window. A whole island or region is seen at its busiest town, not as a haze.
constexpr double kDensestWindow = 800, kDensestCell = 50;

Box2 densest_window(const Scene& scene) {
    Box2 all;
    for (const Building& b : scene.buildings)
        if (!b.outer.empty()) all.extend(b.outer.front());
    if (all.empty() || (all.max.x - all.min.x <= kDensestWindow && all.max.y - all.min.y <= kDensestWindow)) {
        Box2 everything;  // no limit
        everything.extend({-1e300, -1e300});
        everything.extend({1e300, 1e300});
        return everything;
    }
    const int nx = static_cast<int>((all.max.x - all.min.x) / kDensestCell) + 1;
    const int ny = static_cast<int>((all.max.y - all.min.y) / kDensestCell) + 1;
    // Floor area summed over [0, i) x [0, j) cells (a summed-area table).
    std::vector<double> sum(static_cast<size_t>(nx + 1) * (ny + 1), 0.0);
    auto at = [&](int i, int j) -> double& { return sum[static_cast<size_t>(j) * (nx + 1) + i]; };
    for (const Building& b : scene.buildings) {
        if (b.outer.empty() || b.is_part) continue;
        const int i = static_cast<int>((b.outer.front().x - all.min.x) / kDensestCell);
        const int j = static_cast<int>((b.outer.front().y - all.min.y) / kDensestCell);
        at(i + 1, j + 1) += std::fabs(signed_area(b.outer));
    }
    for (int j = 1; j <= ny; ++j)
        for (int i = 1; i <= nx; ++i) at(i, j) += at(i - 1, j) + at(i, j - 1) - at(i - 1, j - 1);
    const int w = static_cast<int>(kDensestWindow / kDensestCell);
    double best = -1;
    int best_i = 0, best_j = 0;
    for (int j = 0; j + std::min(w, ny) <= ny; ++j)
        for (int i = 0; i + std::min(w, nx) <= nx; ++i) {
            const int i1 = std::min(nx, i + w), j1 = std::min(ny, j + w);
            const double area = at(i1, j1) - at(i, j1) - at(i1, j) + at(i, j);
            if (area > best) best = area, best_i = i, best_j = j;
        }
    Box2 window;
    window.extend({all.min.x + best_i * kDensestCell, all.min.y + best_j * kDensestCell});
    window.extend({all.min.x + (best_i + w) * kDensestCell, all.min.y + (best_j + w) * kDensestCell});
    return window;
}

bool inside(const Box2& box, Vec2 p) { return p.x >= box.min.x && p.x <= box.max.x && p.y >= box.min.y && p.y <= box.max.y; }

TownExtent town_extent(const Scene& scene) {
    TownExtent town;
    Box2& box = town.box;
    const Box2 window = densest_window(scene);
    std::vector<const Building*> buildings;
    for (const Building& b : scene.buildings)
        if (!b.outer.empty() && inside(window, b.outer.front())) buildings.push_back(&b);
    for (const Building* b : buildings) {
        for (Vec2 p : b->outer) box.extend(p);
        town.top = std::max(town.top, b->height);
    }
    if (box.empty())
        for (const RoadEdge& r : scene.roads)
            for (Vec2 p : r.quad) box.extend(p);
    if (box.empty()) {
        box.extend(scene.header.bounds_min);
        box.extend(scene.header.bounds_max);
    }
    town.radius = std::max(20.0, 0.5 * std::hypot(box.max.x - box.min.x, box.max.y - box.min.y));
    for (const Building* b : buildings) {
        const double base = building_base(scene, *b);
        for (Vec2 p : b->outer) {
            town.corners.push_back({p.x, p.y, base});
            town.corners.push_back({p.x, p.y, base + std::min(b->height, 2 * town.radius)});
        }
    }
    if (town.corners.empty())
        for (double x : {box.min.x, box.max.x})
            for (double y : {box.min.y, box.max.y}) town.corners.push_back({x, y, ground_height(scene, x, y)});
    return town;
}

double quantile(std::vector<double>& values, double q) {
    const size_t k = std::min(values.size() - 1, static_cast<size_t>(q * values.size()));
    std::nth_element(values.begin(), values.begin() + k, values.end());
    return values[k];
}

// A view direction and frame size, and the corners it must show: every corner inside 90% of
// the frame, but for a lone building far out of town (0.3% of the corners may fall outside).
struct FramingView {
    Vec3 back, forward, right, up;
    double tan_v, tan_h;
    const std::vector<Vec3>& corners;

    bool fits(Vec3 target, double distance) const {
        const size_t allowed_outside = corners.size() * 3 / 1000;
        const Vec3 eye = target + back * distance;
        size_t outside = 0;
        for (const Vec3& c : corners) {
            const Vec3 d = c - eye;
            const double z = dot(d, forward);
            if (z <= 0 || std::fabs(dot(d, right)) > tan_h * z || std::fabs(dot(d, up)) > tan_v * z)
                if (++outside > allowed_outside) return false;
        }
        return true;
    }
    // The nearest distance that fits, by bisection (fitting gets easier with distance).
    double nearest_fit(Vec3 target, double radius) const {
        double near = 0.01 * radius, far = 100 * radius;
        for (int i = 0; i < 60; ++i) {
            const double mid = 0.5 * (near + far);
            (fits(target, mid) ? far : near) = mid;
        }
        return far;
    }
    // The target moved towards the middle of what the corners cover in the image, damped:
    // perspective shifts too.
    Vec3 recentred(Vec3 target, double distance) const {
        const Vec3 eye = target + back * distance;
        std::vector<double> u, v;
        for (const Vec3& c : corners) {
            const Vec3 d = c - eye;
            const double z = std::max(dot(d, forward), 1e-9);
            u.push_back(dot(d, right) / z);
            v.push_back(dot(d, up) / z);
        }
        const double u_mid = 0.5 * (quantile(u, 0.0015) + quantile(u, 0.9985));
        const double v_mid = 0.5 * (quantile(v, 0.0015) + quantile(v, 0.9985));
        return target + (right * u_mid + up * v_mid) * (0.5 * distance);
    }
};

}  // namespace

Vec3 above_ground(const Scene& scene, Vec3 position) {
    return {position.x, position.y,
            std::max(position.z, ground_height(scene, position.x, position.y) + kCameraClearance)};
}

Camera framing_camera(const Scene& scene, double vertical_fov_deg, int width, int height) {
    const TownExtent town = town_extent(scene);
    const Vec2 centre = (town.box.min + town.box.max) * 0.5;
    // Look down 20 degrees, less when the field of view is narrow, so the top of the image
    // always shows some sky above the horizon.
    const double half_fov = 0.5 * vertical_fov_deg * kPi / 180;
    const double pitch = std::clamp(half_fov - 5 * kPi / 180, 3 * kPi / 180, 20 * kPi / 180);
    Vec3 target{centre.x, centre.y, ground_height(scene, centre.x, centre.y) + 0.15 * std::min(town.top, town.radius)};
    const Vec2 from_south_west = normalize(Vec2{-1, -1.6});
    const Vec3 back{from_south_west.x * std::cos(pitch), from_south_west.y * std::cos(pitch), std::sin(pitch)};
    const double tan_v = 0.9 * std::tan(half_fov), tan_h = tan_v * width / height;
    const Vec3 forward = -back;
    const Vec3 right = normalize(cross(forward, Vec3{0, 0, 1}));
    const FramingView view{back, forward, right, cross(right, forward), tan_v, tan_h, town.corners};
    // A few rounds of: fit the distance, then re-aim at the middle of what the town covers in
    // the image (a town seen from above fills the lower half otherwise). The direction, and so
    // the strip of sky at the top, stays the same.
    for (int round = 0; round < 8; ++round) target = view.recentred(target, view.nearest_fit(target, town.radius));
    const Vec3 position = above_ground(scene, target + back * view.nearest_fit(target, town.radius));
    return Camera::look_at(position, target, vertical_fov_deg, width, height);
}

}  // namespace citygen
