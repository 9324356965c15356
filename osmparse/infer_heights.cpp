#include "infer_heights.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>

#include "clean_footprint.h"
#include "rng.h"

namespace citygen {

namespace {

const char* const kHeights = "building heights";
constexpr double kNeighbourRadius = 150;  // metres
constexpr size_t kMaxNeighbours = 8;
enum Salt : uint64_t { kJitter = 201 };

bool is_one_of(const std::string& value, std::initializer_list<const char*> list) {
    for (const char* s : list)
        if (value == s) return true;
    return false;
}

struct Tagged {
    Vec2 at;
    double height;
    const std::string* type;
};

// Centroids of tagged buildings in square cells of the neighbour radius.
class TaggedGrid {
public:
    explicit TaggedGrid(std::vector<Tagged> items) : items_(std::move(items)) {
        for (size_t i = 0; i < items_.size(); ++i) cells_[key(cell(items_[i].at.x), cell(items_[i].at.y))].push_back(i);
    }
    // Up to kMaxNeighbours nearest within the radius, nearest first (ties by index: deterministic).
    std::vector<std::pair<double, size_t>> nearest(Vec2 p) const {
        std::vector<std::pair<double, size_t>> found;
        const int64_t cx = cell(p.x), cy = cell(p.y);
        for (int64_t dx = -1; dx <= 1; ++dx)
            for (int64_t dy = -1; dy <= 1; ++dy) {
                auto it = cells_.find(key(cx + dx, cy + dy));
                if (it == cells_.end()) continue;
                for (size_t i : it->second) {
                    const double d = length(items_[i].at - p);
                    if (d <= kNeighbourRadius) found.push_back({d, i});
                }
            }
        std::sort(found.begin(), found.end());
        return found;
    }
    const Tagged& operator[](size_t i) const { return items_[i]; }

private:
    static int64_t cell(double v) { return static_cast<int64_t>(std::floor(v / kNeighbourRadius)); }
    static int64_t key(int64_t x, int64_t y) { return x * 73856093 ^ y * 19349663; }
    std::vector<Tagged> items_;
    std::unordered_map<int64_t, std::vector<size_t>> cells_;
};

// Weighted median: the value where the weights on each side balance (nearer counts more).
double weighted_median(std::vector<std::pair<double, double>> values) {  // (value, weight)
    std::sort(values.begin(), values.end());
    double total = 0;
    for (const auto& v : values) total += v.second;
    double run = 0;
    for (const auto& v : values) {
        run += v.second;
        if (run >= 0.5 * total) return v.first;
    }
    return values.back().first;
}

Vec2 centroid(const Ring& ring) {
    Vec2 c{0, 0};
    for (Vec2 p : ring) c = c + p;
    return ring.empty() ? c : c * (1.0 / ring.size());
}

}  // namespace

double height_by_type_and_area(const std::string& type, double area, bool* sure) {
    *sure = true;
    if (area < 30 || is_one_of(type, {"garage", "garages", "carport", "shed", "kiosk", "hut", "toilets",
                                      "transformer_tower", "service", "greenhouse", "cabin"}))
        return 3;
    if (is_one_of(type, {"house", "detached", "semidetached_house", "terrace", "bungalow", "villa"}))
        return type == "bungalow" ? 5 : 8;
    if (is_one_of(type, {"farm_auxiliary", "barn", "stable", "cowshed", "farm"})) return 7;
    *sure = false;
    if (is_one_of(type, {"church", "cathedral"})) return 18;
    if (type == "chapel") return 8;
    if (is_one_of(type, {"apartments", "dormitory"})) return area < 800 ? 15 : 24;
    if (is_one_of(type, {"office", "hotel", "hospital"})) return 18;
    if (is_one_of(type, {"commercial", "civic", "public", "government"})) return 12;
    if (is_one_of(type, {"school", "university", "college", "kindergarten"})) return type == "kindergarten" ? 5 : 10;
    if (is_one_of(type, {"retail", "supermarket"})) return 4;
    if (is_one_of(type, {"industrial", "warehouse", "manufacture", "hangar"})) return 8;
    if (is_one_of(type, {"yes", "residential", "building"})) {
        if (area < 80) return 4;
        if (area < 200) return 7;
        if (area < 600) return 10;
        return area < 1500 ? 15 : 21;  // large footprints in towns are blocks of flats or offices
    }
    return 0;
}

void infer_heights(std::vector<Building>& buildings, const BuildingParams& params, ParseReport& report) {
    std::vector<Tagged> tagged;
    for (const Building& b : buildings)
        if (b.height_source != HeightSource::Random && b.min_height == 0 && !b.is_part)
            tagged.push_back({centroid(b.outer), b.height, &b.type});
    const TaggedGrid grid(std::move(tagged));

    for (Building& b : buildings) {
        if (b.height_source == HeightSource::Tagged) b.height_rule = HeightRule::Tagged;
        if (b.height_source == HeightSource::Levels) b.height_rule = HeightRule::Levels;
        if (b.height_source != HeightSource::Random) continue;
        b.height_rule = HeightRule::Random;
        if (b.min_height > 0) continue;  // a raised part: building_heights gave it a storey
        const double area = std::fabs(signed_area(b.outer));
        bool sure = false;
        const double by_type = height_by_type_and_area(b.type, area, &sure);
        double height = 0;
        if (sure) {
            height = by_type;
            b.height_rule = HeightRule::TypeAndArea;
        } else {
            const auto near = grid.nearest(centroid(b.outer));
            std::vector<std::pair<double, double>> same, all;
            for (const auto& [d, i] : near) {
                const double w = 1 / (d + 20);
                if (all.size() < kMaxNeighbours) all.push_back({grid[i].height, w});
                if (*grid[i].type == b.type && same.size() < kMaxNeighbours) same.push_back({grid[i].height, w});
            }
            if (same.size() >= 2 || all.size() >= 3) {
                height = weighted_median(same.size() >= 2 ? same : all);
                b.height_rule = HeightRule::Neighbours;
            } else if (by_type > 0) {
                height = by_type;
                b.height_rule = HeightRule::TypeAndArea;
            }
        }
        if (b.height_rule == HeightRule::Random) {
            report.note(kHeights, "random (no rule applied)");
            continue;
        }
        const double u = hash_to_unit(hash_keys(params.seed, static_cast<uint64_t>(b.osm.type),
                                                static_cast<uint64_t>(b.osm.id), kJitter));
        b.height = std::clamp(height * (0.9 + 0.2 * u), 2.5, params.max_height);
        b.levels = std::max(1, static_cast<int>(std::lround(b.height / params.level_height)));
        report.note(kHeights, b.height_rule == HeightRule::Neighbours ? "from tagged neighbours"
                                                                       : "from type and footprint area");
    }
}

}  // namespace citygen
