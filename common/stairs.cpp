#include "common/stairs.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "common/ground.h"

namespace citygen {

double StairPlan::line_height(Vec2 p) const {
    const double along = dot(p - low, normalize(high - low)) / run();
    return z_low + std::clamp(along, 0.0, 1.0) * (z_high - z_low);
}

bool plan_stair(const Scene& scene, const PathEdge& path, StairPlan* plan) {
    if (!stair_between_ends(scene.terrain, path, plan)) return false;
    // The ground along the centreline, every half cell between the ends, against the treads'
    // tops (at most a riser above the line): a riser of ground over a tread hides it. A stair
    // hidden in part still reads as one; hidden over most of its run it does not.
    const HeightField& field = scene.terrain;
    const int samples = static_cast<int>(std::ceil(plan->run() / (0.5 * field.cell)));
    int hidden = 0;
    for (int k = 1; k < samples; ++k) {
        const Vec2 p = plan->low + (plan->high - plan->low) * (static_cast<double>(k) / samples);
        hidden += field_surface_height(field, p.x, p.y) > plan->line_height(p) + 2 * kStairMaxRiser;
    }
    return 2 * hidden <= samples - 1;
}

bool stair_between_ends(const HeightField& field, const PathEdge& path, StairPlan* plan) {
    if (field.empty() || path.path_class != PathClass::Steps || path.bridge) return false;  // a deck's steps: the deck
    if (path.quad.size() != 4 || path.centreline.size() < 2) return false;
    const Vec2 a = path.centreline.front(), u = normalize(path.centreline.back() - a);
    if (!(length(u) > 0)) return false;
    // The strip's two end edges: its two corners nearest each node along the centreline.
    std::array<double, 4> along;
    for (size_t k = 0; k < 4; ++k) along[k] = dot(path.quad[k] - a, u);
    std::array<size_t, 4> order = {0, 1, 2, 3};
    std::sort(order.begin(), order.end(), [&](size_t i, size_t j) { return along[i] < along[j]; });
    const auto centre = [&](size_t i, size_t j) { return a + u * (0.5 * (along[i] + along[j])); };
    Vec2 ends[2] = {centre(order[0], order[1]), centre(order[2], order[3])};
    double z[2];
    for (int e = 0; e < 2; ++e) z[e] = field_surface_height(field, ends[e].x, ends[e].y);
    const double run = length(ends[1] - ends[0]), rise = std::fabs(z[1] - z[0]);
    if (!(run > 0.01) || !std::isfinite(rise) || !(rise > kStairMinGrade * run)) return false;
    const int low = z[0] <= z[1] ? 0 : 1;
    plan->low = ends[low];
    plan->high = ends[1 - low];
    plan->z_low = z[low];
    plan->z_high = z[1 - low];
    const double steps = std::ceil(rise / kStairMaxRiser - 1e-9);
    if (steps > kMaxStairSteps) return false;  // a cliff, or a hostile file's heights: draped
    plan->steps = static_cast<int>(steps);
    return true;
}

}  // namespace citygen
