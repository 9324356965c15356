#include "build_roofs.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>

#include "osm_units.h"
#include "rng.h"
#include "roof_geometry.h"

namespace citygen {

namespace {

const char* const kRoofs = "roofs";
constexpr double kPi = 3.141592653589793;
constexpr double kMinRoofHeight = 0.3;  // lower than this, a roof is drawn flat

enum Salt : uint64_t { kPitchedOrFlat = 101, kWhichPitched, kPitch };

bool is_one_of(const std::string& value, std::initializer_list<const char*> list) {
    for (const char* s : list)
        if (value == s) return true;
    return false;
}

// Pitch (degrees) a shape gets when neither roof:height, roof:levels nor roof:angle is tagged.
double default_pitch(RoofShape shape) {
    switch (shape) {
        case RoofShape::Skillion: return 15;
        case RoofShape::Hipped: return 30;
        case RoofShape::Gambrel:
        case RoofShape::Mansard: return 50;
        default: return 35;
    }
}

// A roof height from the pitch and the footprint: the rise over half the width for a ridge
// roof, over the whole width for a skillion; domes and onions scale with the radius.
double height_from_pitch(RoofShape shape, double pitch_deg, const RoofFrame& frame) {
    const double half = 0.5 * frame.width(), rise = std::tan(pitch_deg * kPi / 180);
    switch (shape) {
        case RoofShape::Skillion: return rise * frame.width();
        case RoofShape::Dome: return half;
        case RoofShape::Onion: return 1.5 * half;
        case RoofShape::Round: return half;
        default: return rise * half;
    }
}

Vec3 newell_normal(const std::vector<Vec3>& p) {
    Vec3 n{0, 0, 0};
    for (size_t i = 0; i < p.size(); ++i) {
        const Vec3 a = p[i] - p[0], b = p[(i + 1) % p.size()] - p[0];
        n = n + Vec3{(a.y - b.y) * (a.z + b.z), (a.z - b.z) * (a.x + b.x), (a.x - b.x) * (a.y + b.y)};
    }
    return normalize(n);
}

}  // namespace

bool parse_roof_shape(const char* text, RoofShape* shape) {
    static const std::pair<const char*, RoofShape> names[] = {
        {"flat", RoofShape::Flat},           {"skillion", RoofShape::Skillion},
        {"lean_to", RoofShape::Skillion},    {"gabled", RoofShape::Gabled},
        {"pitched", RoofShape::Gabled},      {"saltbox", RoofShape::Gabled},
        {"hipped", RoofShape::Hipped},       {"side_hipped", RoofShape::Hipped},
        {"crosspitched", RoofShape::Hipped}, {"half-hipped", RoofShape::HalfHipped},
        {"half_hipped", RoofShape::HalfHipped}, {"pyramidal", RoofShape::Pyramidal},
        {"cone", RoofShape::Pyramidal},      {"gambrel", RoofShape::Gambrel},
        {"mansard", RoofShape::Mansard},     {"dome", RoofShape::Dome},
        {"onion", RoofShape::Onion},         {"round", RoofShape::Round},
    };
    for (const auto& [name, value] : names)
        if (std::strcmp(text, name) == 0) {
            *shape = value;
            return true;
        }
    return false;
}

bool parse_compass_direction(const char* text, double* degrees) {
    static const char* const points[] = {"N", "NNE", "NE", "ENE", "E", "ESE", "SE", "SSE",
                                         "S", "SSW", "SW", "WSW", "W", "WNW", "NW", "NNW"};
    for (int i = 0; i < 16; ++i)
        if (std::strcmp(text, points[i]) == 0) {
            *degrees = 22.5 * i;
            return true;
        }
    char* end = nullptr;
    const double v = std::strtod(text, &end);
    if (end == text || *end != '\0' || !std::isfinite(v)) return false;
    *degrees = std::fmod(std::fmod(v, 360.0) + 360.0, 360.0);
    return true;
}

RoofShape default_roof(const Building& b, double area, uint64_t seed, double* pitch_deg) {
    const uint64_t key = hash_keys(seed, static_cast<uint64_t>(b.osm.type), static_cast<uint64_t>(b.osm.id));
    const double u = hash_to_unit(hash_keys(key, kPitchedOrFlat));
    const double which = hash_to_unit(hash_keys(key, kWhichPitched));
    *pitch_deg = 25 + 20 * hash_to_unit(hash_keys(key, kPitch));
    auto pitched = [&] {
        return which < 0.65 ? RoofShape::Gabled : which < 0.9 ? RoofShape::Hipped : RoofShape::HalfHipped;
    };
    if (b.is_part || b.min_height > 0) return RoofShape::Flat;
    const std::string& t = b.type;
    const double h = b.height;
    if (is_one_of(t, {"church", "chapel", "cathedral", "barn", "farm_auxiliary", "stable", "cowshed"}))
        return RoofShape::Gabled;
    if (is_one_of(t, {"house", "detached", "semidetached_house", "terrace", "bungalow", "farm", "villa",
                      "cabin", "hut", "static_caravan", "dormitory"}))
        return pitched();
    if (is_one_of(t, {"garage", "garages", "shed", "carport"}))
        return u < 0.5 ? RoofShape::Flat : u < 0.8 ? RoofShape::Gabled : RoofShape::Skillion;
    if (is_one_of(t, {"yes", "residential"}) && area < 250 && h <= 13) return u < 0.6 ? pitched() : RoofShape::Flat;
    if (t == "apartments" && area < 600 && h <= 20) return u < 0.3 ? pitched() : RoofShape::Flat;
    return RoofShape::Flat;
}

bool roof_face_is_valid(const RoofFace& face, const Building& b, double z_min, double z_max) {
    const double tol = 1e-2;
    if (face.points.size() < 3) return false;
    const Vec3 n = newell_normal(face.points);
    if (length(n) < 0.5) return false;  // no area
    const double d = dot(n, face.points[0]);
    for (Vec3 p : face.points) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
        if (std::fabs(dot(n, p) - d) > tol) return false;
        if (p.z < z_min - tol || p.z > z_max + tol) return false;
        const Vec2 q{p.x, p.y};
        if (!point_in_ring(q, b.outer) && distance_to_boundary(q, b.outer) > tol) return false;
        for (const Ring& hole : b.holes)
            if (point_in_ring(q, hole) && distance_to_boundary(q, hole) > tol) return false;
    }
    return true;
}

void build_roofs(std::vector<Building>& buildings, const BuildingTagIndex& index, const BuildingParams& params,
                 ParseReport& report) {
    for (Building& b : buildings) {
        b.roof_faces.clear();
        b.roof_height = 0;
        b.roof_shape = RoofShape::Flat;
        if (b.outer.size() < 3 || !(b.height > b.min_height)) continue;
        const OsmTags& tags = index.find(b.osm);
        const double area = std::fabs(signed_area(b.outer));

        // Shape.
        RoofShape shape = RoofShape::Flat;
        double pitch = 0;
        b.roof_inferred = false;
        if (const char* text = tags.get("roof:shape")) {
            if (!parse_roof_shape(text, &shape)) {
                report.note(kRoofs, "unknown roof:shape: flat");
                shape = RoofShape::Flat;
            }
            pitch = default_pitch(shape);
        } else {
            shape = default_roof(b, area, params.seed, &pitch);
            b.roof_inferred = true;
        }
        if (const char* text = tags.get("roof:angle")) {
            char* end = nullptr;
            const double angle = std::strtod(text, &end);
            if (end != text && *end == '\0' && angle > 0 && angle <= 85) pitch = angle;
            else report.note(kRoofs, "bad roof:angle ignored");
        }
        if (shape == RoofShape::Flat) {
            report.note(kRoofs, b.roof_inferred ? "flat (default)" : "flat (tagged)");
            continue;
        }

        RoofSpec spec;
        spec.shape = shape;
        if (const char* text = tags.get("roof:direction")) {
            double degrees = 0;
            if (parse_compass_direction(text, &degrees)) {
                spec.has_direction = true;
                spec.direction = {std::sin(degrees * kPi / 180), std::cos(degrees * kPi / 180)};
            } else {
                report.note(kRoofs, "bad roof:direction ignored");
            }
        }
        spec.across = tags.has("roof:orientation", "across");

        // Height.
        const double budget = b.height - b.min_height;
        double height = 0;
        bool derived = false;
        const char* height_text = tags.get("roof:height");
        std::optional<double> tagged = height_text ? parse_osm_length(height_text) : std::nullopt;
        if (height_text && (!tagged || *tagged < 0)) {
            report.note(kRoofs, "bad roof:height ignored");
            tagged.reset();
        }
        const char* levels_text = tags.get("roof:levels");
        std::optional<double> levels = levels_text ? parse_osm_count(levels_text) : std::nullopt;
        if (tagged) {
            height = *tagged;
        } else if (levels && *levels > 0 && *levels < 100) {
            height = *levels * params.level_height;
        } else {
            height = height_from_pitch(shape, pitch, roof_frame(b.outer, spec));
            derived = true;
        }
        if (b.height_source == HeightSource::Levels) {
            b.height += height;  // building:levels counts the storeys under the roof
        } else if (derived) {
            height = std::min(height, 0.75 * budget);
        } else if (height > budget) {
            report.note(kRoofs, "roof:height above the building: clamped");
            height = budget;
        }
        if (height < kMinRoofHeight) {
            report.note(kRoofs, "roof too low: flat");
            continue;
        }

        spec.eaves_z = b.height - height;
        spec.height = height;
        std::vector<RoofFace> faces;
        RoofShape built = shape;
        std::string why;
        if (!make_roof_faces(b.outer, b.holes, spec, &faces, &built, &why)) {
            report.note(kRoofs, "could not build (" + why + "): flat");
            if (b.height_source == HeightSource::Levels) b.height -= height;
            continue;
        }
        for (RoofFace& wall : gable_walls(b.outer, b.holes, faces, spec.eaves_z)) faces.push_back(std::move(wall));
        bool valid = true;
        for (const RoofFace& face : faces) valid = valid && roof_face_is_valid(face, b, spec.eaves_z, b.height);
        if (!valid) {
            report.note(kRoofs, std::string("faces failed the checks (") + to_string(shape) + "): flat");
            if (b.height_source == HeightSource::Levels) b.height -= height;
            continue;
        }
        if (built != shape)
            report.note(kRoofs, std::string(to_string(shape)) + " on a bent or holed footprint: built hipped");
        b.roof_shape = built;
        b.roof_height = height;
        b.roof_faces = std::move(faces);
        report.note(kRoofs, std::string(to_string(built)) + (b.roof_inferred ? " (default)" : " (tagged)"));
    }
}

}  // namespace citygen
