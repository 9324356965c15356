#include "render/integrator/small_emitters.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_sort.h>

#include "common/rng.h"
#include "render/integrator/pixel_jitter.h"
#include "render/lights/scene_lights.h"
#include "render/materials/materials.h"

namespace citygen {

namespace {

// The pair of a pixel's stratified numbers (pixel_jitter.h) that places the rays at emitters;
// the first surface takes pairs 1-4 (render_image.cpp).
constexpr uint32_t kEmitterPair = 5;
// Keys the picks among a pixel's emitters when there are more than SmallEmitters::kMaxRaysPerSample.
constexpr uint64_t kPickSalt = 0x9c75;

bool is_pane(const Hit& hit) { return hit.material == kGlass || hit.material == kShopWindow; }

}  // namespace

bool SmallEmitters::Rectangle::matches(const Hit& hit) const {
    if (cell == 0) return hit.kind == ObjectKind::Lamp && hit.object == object && hit.material == kLampGlobe;
    return hit.kind == ObjectKind::Building && hit.object == object && hit.wall == wall && hit.cell == cell &&
           is_pane(hit);
}

bool SmallEmitters::fits(const Camera& camera, double x0, double y0, double x1, double y1) {
    if (x1 - x0 > kMaxPixels || y1 - y0 > kMaxPixels) return false;
    // Off the image no camera ray meets it.
    return std::floor(x1) >= 0 && std::floor(x0) <= camera.width() - 1 && std::floor(y1) >= 0 &&
           std::floor(y0) <= camera.height() - 1;
}

bool SmallEmitters::add(const Camera& camera, Rectangle r, double x0, double y0, double x1, double y1) {
    if (!fits(camera, x0, y0, x1, y1)) return false;
    const int first_x = std::max(0, static_cast<int>(std::floor(x0)));
    const int last_x = std::min(camera.width() - 1, static_cast<int>(std::floor(x1)));
    const int first_y = std::max(0, static_cast<int>(std::floor(y0)));
    const int last_y = std::min(camera.height() - 1, static_cast<int>(std::floor(y1)));
    r.x0 = float(x0), r.y0 = float(y0), r.x1 = float(x1), r.y1 = float(y1);
    const uint32_t rectangle = static_cast<uint32_t>(rectangles_.size());
    rectangles_.push_back(r);
    for (int y = first_y; y <= last_y; ++y)
        for (int x = first_x; x <= last_x; ++x) covers_.push_back({static_cast<uint64_t>(y) * width_ + x, rectangle});
    return true;
}

SmallEmitters::SmallEmitters(const SceneLights& lights, const Camera& camera, bool panes) : width_(camera.width()) {
    small_.assign(lights.lamp_count(), 0);
    for (uint32_t lamp = 0; lamp < lights.lamp_count(); ++lamp) {
        // The projected corners of a cube around the globe bound its image; 1.5 radii also hold
        // the facets of a stored globe (stored_lamps.cpp), which lie a little outside the sphere.
        const Vec3 c = lights.lamp_center(lamp);
        const double h = 1.5 * lights.lamp_radius(lamp);
        double x0 = 1e30, y0 = 1e30, x1 = -1e30, y1 = -1e30;
        bool in_front = true;
        for (int corner = 0; corner < 8 && in_front; ++corner) {
            const Vec3 p = c + Vec3{corner & 1 ? h : -h, corner & 2 ? h : -h, corner & 4 ? h : -h};
            double px, py;
            in_front = camera.project(p, &px, &py);
            x0 = std::min(x0, px), x1 = std::max(x1, px), y0 = std::min(y0, py), y1 = std::max(y1, py);
        }
        if (in_front && add(camera, Rectangle{lamp, 0, 0, 0, 0, 0, 0}, x0, y0, x1, y1)) small_[lamp] = 1;
    }
    if (panes) {
        // A pane is flat: the projected corners of (the visible part of) it bound its image.
        auto image_bounds = [&camera](const SceneLights::SeenPane& pane, double* x0, double* y0, double* x1,
                                      double* y1) {
            *x0 = 1e30, *y0 = 1e30, *x1 = -1e30, *y1 = -1e30;
            for (const Vec3& p : pane.corner) {
                double px, py;
                if (!camera.project(p, &px, &py)) return false;
                *x0 = std::min(*x0, px), *x1 = std::max(*x1, px), *y0 = std::min(*y0, py), *y1 = std::max(*y1, py);
            }
            return true;
        };
        lights.for_each_lit_pane(
            camera.position(),
            [&](const SceneLights::SeenPane& pane) {
                double x0, y0, x1, y1;
                return image_bounds(pane, &x0, &y0, &x1, &y1) && fits(camera, x0, y0, x1, y1);
            },
            [&](const SceneLights::SeenPane& pane) {
                double x0, y0, x1, y1;
                image_bounds(pane, &x0, &y0, &x1, &y1);
                add(camera, Rectangle{pane.building, pane.wall, pane.cell, 0, 0, 0, 0}, x0, y0, x1, y1);
            });
    }
    // Both orders are total (no two entries equal), so the parallel sorts are deterministic.
    tbb::parallel_sort(covers_.begin(), covers_.end());
    size_t pane_count = 0;
    for (const Rectangle& r : rectangles_) pane_count += r.cell != 0;
    panes_.reserve(pane_count);
    for (const Rectangle& r : rectangles_)
        if (r.cell != 0) panes_.push_back({r.object, r.wall, r.cell});
    tbb::parallel_sort(panes_.begin(), panes_.end());
}

bool SmallEmitters::counts_on_film(const Hit& hit) const {
    if (hit.kind == ObjectKind::Lamp)
        return hit.material == kLampGlobe && hit.object < small_.size() && small_[hit.object];
    if (hit.kind != ObjectKind::Building || hit.cell == 0 || panes_.empty() || !is_pane(hit)) return false;
    return std::binary_search(panes_.begin(), panes_.end(), PaneId{hit.object, hit.wall, hit.cell});
}

SmallEmitters::InPixel SmallEmitters::in_pixel(int x, int y) const {
    const uint64_t pixel = static_cast<uint64_t>(y) * width_ + x;
    const auto first = std::lower_bound(covers_.begin(), covers_.end(), Cover{pixel, 0});
    auto last = first;
    while (last != covers_.end() && last->pixel == pixel) ++last;
    return {static_cast<size_t>(first - covers_.begin()), static_cast<size_t>(last - covers_.begin())};
}

Color SmallEmitters::light_in_pixel(InPixel emitters, const PathContext& context, const Camera& camera, int x, int y,
                                    uint64_t pixel_key, uint32_t index, uint64_t& rays) const {
    // The part of the pixel inside a rectangle: [x0, x1] x [y0, y1], empty if not x1 > x0 and y1 > y0.
    struct Part {
        double x0, y0, x1, y1;
        double area() const { return x1 > x0 && y1 > y0 ? (x1 - x0) * (y1 - y0) : 0.0; }
    };
    auto part_of = [&](const Rectangle& r) {
        return Part{std::max<double>(r.x0, x), std::max<double>(r.y0, y), std::min<double>(r.x1, x + 1),
                    std::min<double>(r.y1, y + 1)};
    };
    // The emitter's light along a ray at point u of the part, times `weight`, if the ray meets its front.
    auto light_at = [&](const Rectangle& r, const Part& part, Vec2 u, double weight) {
        const Ray ray = camera.generate_ray(part.x0 + u.x * (part.x1 - part.x0), part.y0 + u.y * (part.y1 - part.y0));
        Hit hit;
        ++rays;
        if (!context.scene.intersect(ray, hit) || !r.matches(hit) || !(dot(hit.geometric_normal, ray.direction) < 0))
            return Color{0, 0, 0};
        // As trace_path's camera ray: haze, and the chance of crossing the fog unscattered.
        double transmittance = 1;
        const IntegratorSettings& settings = context.settings;
        if (settings.haze_extinction > 0) transmittance *= aerial_transmittance(settings.haze_extinction, hit.t);
        if (settings.fog.on()) transmittance *= settings.fog.transmittance(ray.origin, ray.direction, hit.t);
        return context.lights->emitted(hit) * (transmittance * weight);
    };
    Color sum{0, 0, 0};
    if (emitters.last - emitters.first <= kMaxRaysPerSample) {  // a ray at each
        for (size_t at = emitters.first; at < emitters.last; ++at) {
            const Rectangle& r = rectangles_[covers_[at].rectangle];
            const Part part = part_of(r);
            if (!(part.area() > 0)) continue;
            const uint64_t key =
                r.cell == 0 ? hash_keys(pixel_key, r.object) : hash_keys(pixel_key, r.object, r.wall, r.cell);
            sum = sum + light_at(r, part, stratified_pair(key, index, kEmitterPair), part.area());
        }
        return sum;
    }
    // More than that (a far city's windows, hundreds to a pixel): kMaxRaysPerSample rays, each at
    // an emitter chosen in proportion to its part's area (systematic picks from one stratified
    // number) and weighted by the total area over the picks: the same sum in expectation.
    double total = 0;
    size_t last = emitters.first;  // the last with some area: rounding leaves it the picks beyond the sum
    for (size_t at = emitters.first; at < emitters.last; ++at) {
        const double area = part_of(rectangles_[covers_[at].rectangle]).area();
        total += area;
        if (area > 0) last = at;
    }
    if (!(total > 0)) return sum;
    const double start = stratified_pair(hash_keys(pixel_key, kPickSalt), index, kEmitterPair).x;
    double below = 0;  // the areas of the emitters before `at`
    int pick = 0;
    for (size_t at = emitters.first; at <= last && pick < kMaxRaysPerSample; ++at) {
        const Rectangle& r = rectangles_[covers_[at].rectangle];
        const Part part = part_of(r);
        const double area = part.area();
        for (; pick < kMaxRaysPerSample; ++pick) {
            const double target = (start + pick) / kMaxRaysPerSample * total;
            if (!(target < below + area) && at < last) break;
            const Vec2 u = stratified_pair(hash_keys(pixel_key, kPickSalt, static_cast<uint64_t>(pick)), index, kEmitterPair);
            sum = sum + light_at(r, part, u, total / kMaxRaysPerSample);
        }
        below += area;
    }
    return sum;
}

}  // namespace citygen
