#include "osmparse/terrain/retaining_wall_steps.h"

#include <algorithm>
#include <cmath>

#include "common/grid_nodes.h"
#include "common/ground.h"
#include "osmparse/terrain/fit_terrain.h"

namespace citygen {

void step_terrain_at_walls(HeightField& field, const std::vector<RetainingWall>& walls,
                           const std::vector<uint8_t>& under_ways, ParseReport& report) {
    if (field.empty() || walls.empty()) return;
    const GridLayout g{field.origin, field.cell, field.nx, field.ny};
    // Every cell the wall's line crosses has its low-side nodes within this of it: the drawn
    // ground there falls by the wall's height within that cell.
    const double foot = field.cell * std::sqrt(2.0);
    const double shoulder = shoulder_width(field);
    const HeightField before = field;  // the high sides' ground, whatever order the walls come in
    enum : uint8_t { kLeft = 0, kFoot = 1, kShoulder = 2 };
    std::vector<uint8_t> by(field.heights.size(), kLeft);
    int64_t unstepped = 0;
    for (const RetainingWall& wall : walls) {
        const std::vector<Vec2>& line = wall.line;
        const bool closed = line.size() > 2 && line.front() == line.back();
        bool stepped = false, blocked = false;
        for (size_t k = 0; k + 1 < line.size(); ++k) {
            const Vec2 a = line[k], b = line[k + 1], d = b - a;
            const double length2 = dot(d, d);
            if (!(length2 > 0)) continue;
            // Beyond the wall's open ends the ground is left: the step ends with the wall.
            const bool open_start = k == 0 && !closed, open_end = k + 2 == line.size() && !closed;
            for_each_node_near(g, a, b, foot + shoulder, [&](uint32_t i, uint32_t j, double distance, double t) {
                const Vec2 p = g.node(i, j);
                if (!(cross(d, p - a) < 0)) return;  // the high side (left), or on the line
                const double u = dot(p - a, d) / length2;
                if ((open_start && u < 0) || (open_end && u > 1)) return;
                const size_t n = g.index(i, j);
                const bool at_foot = distance <= foot;
                if (under_ways[n]) {
                    blocked = blocked || at_foot;
                    return;
                }
                const Vec2 q = a + d * t;
                const double low = field_surface_height(before, q.x, q.y) - wall.height;
                const double weight = shoulder_weight(distance - foot, shoulder);
                const auto h = static_cast<float>(weight * low + (1 - weight) * before.heights[n]);
                if (h < field.heights[n]) {
                    field.heights[n] = h;
                    by[n] = at_foot ? kFoot : kShoulder;
                    stepped = stepped || at_foot;
                }
            });
        }
        unstepped += blocked && !stepped;
    }
    const auto count = [&](uint8_t what) { return static_cast<int64_t>(std::count(by.begin(), by.end(), what)); };
    if (const int64_t n = count(kFoot)) report.note(ReportKind::TerrainNodes, ReportReason::TerrainAtRetainingWall, n);
    if (const int64_t n = count(kShoulder))
        report.note(ReportKind::TerrainNodes, ReportReason::TerrainRetainingWallShoulder, n);
    if (unstepped > 0) report.note(ReportKind::RetainingWalls, ReportReason::RetainingWallUnderWays, unstepped);
}

}  // namespace citygen
