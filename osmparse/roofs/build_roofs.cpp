#include "osmparse/roofs/build_roofs.h"

#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "common/rng.h"
#include "osmparse/core/osm_units.h"
#include "osmparse/roofs/roof_geometry.h"

namespace citygen {

namespace {
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

RoofGroup roof_group(const Building& b, double area) {
    if (b.is_part || b.min_height > 0) return RoofGroup::Flat;
    const std::string& t = b.type;
    if (is_one_of(t, {"church", "chapel", "cathedral", "barn", "farm_auxiliary", "stable", "cowshed"}))
        return RoofGroup::Sacred;
    if (is_one_of(t, {"house", "detached", "semidetached_house", "terrace", "bungalow", "farm", "villa",
                      "cabin", "hut", "static_caravan", "dormitory"}))
        return RoofGroup::Houses;
    if (is_one_of(t, {"garage", "garages", "shed", "carport"})) return RoofGroup::Sheds;
    if (is_one_of(t, {"yes", "residential"}) && area < 250 && b.height <= 13) return RoofGroup::SmallBlocks;
    if (t == "apartments" && area < 600 && b.height <= 20) return RoofGroup::SmallFlats;
    return RoofGroup::Flat;
}

RoofEvidence roof_evidence(const std::vector<Building>& buildings, const BuildingTagIndex& index,
                           const std::function<bool(const Building&)>& counted) {
    RoofEvidence e;
    for (const Building& b : buildings) {
        if (counted && !counted(b)) continue;
        const char* text = index.find(b.osm).get("roof:shape");
        RoofShape shape;
        if (!text || !parse_roof_shape(text, &shape)) continue;
        const int g = static_cast<int>(roof_group(b, std::fabs(signed_area(b.outer))));
        ++e.tagged[g];
        e.pitched[g] += shape != RoofShape::Flat;
    }
    return e;
}

double pitched_share(const RoofEvidence& e, RoofGroup group) {
    // Pseudo-counts of the prior: a handful of tagged roofs already says which way a region
    // builds (flat or pitched is regional: Malta's flat roofs, Germany's gabled ones), and with
    // none the share is the prior's.
    constexpr double kWeight = 4;
    const int g = static_cast<int>(group);
    if (group == RoofGroup::Flat) return 0;
    if (group == RoofGroup::Sacred) return (e.pitched[g] + kWeight) / (e.tagged[g] + kWeight);
    double tagged = 0, pitched = 0;
    for (RoofGroup h : {RoofGroup::Houses, RoofGroup::Sheds, RoofGroup::SmallBlocks, RoofGroup::SmallFlats}) {
        tagged += e.tagged[static_cast<int>(h)];
        pitched += e.pitched[static_cast<int>(h)];
    }
    const double region = pitched / (tagged + kWeight);
    return (e.pitched[g] + kWeight * region) / (e.tagged[g] + kWeight);
}

RoofShape default_roof(const Building& b, double area, uint64_t seed, double* pitch_deg, const RoofEvidence& evidence) {
    const uint64_t key = hash_keys(seed, static_cast<uint64_t>(b.osm.type), static_cast<uint64_t>(b.osm.id));
    const double u = hash_to_unit(hash_keys(key, kPitchedOrFlat));
    const double which = hash_to_unit(hash_keys(key, kWhichPitched));
    *pitch_deg = 25 + 20 * hash_to_unit(hash_keys(key, kPitch));
    const RoofGroup group = roof_group(b, area);
    if (u >= pitched_share(evidence, group)) return RoofShape::Flat;
    if (group == RoofGroup::Sacred) return RoofShape::Gabled;
    if (group == RoofGroup::Sheds) return which < 0.6 ? RoofShape::Gabled : RoofShape::Skillion;
    return which < 0.65 ? RoofShape::Gabled : which < 0.9 ? RoofShape::Hipped : RoofShape::HalfHipped;
}

bool roof_face_is_valid(const RoofFace& face, const Building& b, double z_min, double z_max) {
    const double tol = 1e-2;
    if (!face_is_planar(face, tol)) return false;
    for (Vec3 p : face.points) {
        if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) return false;
        if (p.z < z_min - tol || p.z > z_max + tol) return false;
        const Vec2 q{p.x, p.y};
        if (!point_in_ring(q, b.outer) && distance_to_boundary(q, b.outer) > tol) return false;
        for (const Ring& hole : b.holes)
            if (point_in_ring(q, hole) && distance_to_boundary(q, hole) > tol) return false;
    }
    return true;
}

namespace {

// One building's roof; what the report should count goes to `notes`.
// The roof's shape: tagged, or by the default rules (b.roof_inferred); its pitch: the shape's
// default or roof:angle.
RoofShape roof_shape_and_pitch(Building& b, const OsmTags& tags, double area, const RoofEvidence& evidence,
                               const BuildingParams& params, double* pitch, std::vector<ReportReason>& notes) {
    RoofShape shape = RoofShape::Flat;
    b.roof_inferred = false;
    if (const char* text = tags.get("roof:shape")) {
        if (!parse_roof_shape(text, &shape)) {
            notes.push_back(ReportReason::UnknownRoofShape);
            shape = RoofShape::Flat;
        }
        *pitch = default_pitch(shape);
    } else {
        shape = default_roof(b, area, params.seed, pitch, evidence);
        b.roof_inferred = true;
    }
    if (const char* text = tags.get("roof:angle")) {
        char* end = nullptr;
        const double angle = std::strtod(text, &end);
        if (end != text && *end == '\0' && angle > 0 && angle <= 85) *pitch = angle;
        else notes.push_back(ReportReason::BadRoofAngle);
    }
    return shape;
}

// The shape with its ridge direction and orientation from the tags.
RoofSpec roof_spec(RoofShape shape, const OsmTags& tags, std::vector<ReportReason>& notes) {
    RoofSpec spec;
    spec.shape = shape;
    if (const char* text = tags.get("roof:direction")) {
        double degrees = 0;
        if (parse_compass_direction(text, &degrees)) {
            spec.has_direction = true;
            spec.direction = {std::sin(degrees * kPi / 180), std::cos(degrees * kPi / 180)};
        } else {
            notes.push_back(ReportReason::BadRoofDirection);
        }
    }
    spec.across = tags.has("roof:orientation", "across");
    return spec;
}

// The roof's height: roof:height, else roof:levels, else from the pitch over the footprint (at
// most three quarters of the building). building:levels counts the storeys under the roof, so
// there the roof goes on top (b.height grows); a tagged height above the building is clamped.
double roof_height(Building& b, const OsmTags& tags, const RoofSpec& spec, double pitch,
                   const BuildingParams& params, std::vector<ReportReason>& notes) {
    const double budget = b.height - b.min_height;
    double height = 0;
    bool derived = false;
    const char* height_text = tags.get("roof:height");
    std::optional<double> tagged = height_text ? parse_osm_length(height_text) : std::nullopt;
    if (height_text && (!tagged || *tagged < 0)) {
        notes.push_back(ReportReason::BadRoofHeight);
        tagged.reset();
    }
    const char* levels_text = tags.get("roof:levels");
    std::optional<double> levels = levels_text ? parse_osm_count(levels_text) : std::nullopt;
    if (tagged) {
        height = *tagged;
    } else if (levels && *levels > 0 && *levels < 100) {
        height = *levels * params.level_height;
    } else {
        height = height_from_pitch(spec.shape, pitch, roof_frame(b.outer, spec));
        derived = true;
    }
    if (b.height_source == HeightSource::Levels) {
        b.height += height;
    } else if (derived) {
        height = std::min(height, 0.75 * budget);
    } else if (height > budget) {
        notes.push_back(ReportReason::RoofHeightClamped);
        height = budget;
    }
    return height;
}

void build_roof(Building& b, const BuildingTagIndex& index, const RoofEvidence& evidence, const BuildingParams& params,
                std::vector<ReportReason>& notes) {
    b.roof_faces.clear();
    b.roof_height = 0;
    b.roof_shape = RoofShape::Flat;
    if (!has_volume(b)) return;
    const OsmTags& tags = index.find(b.osm);
    const double area = std::fabs(signed_area(b.outer));

    double pitch = 0;
    const RoofShape shape = roof_shape_and_pitch(b, tags, area, evidence, params, &pitch, notes);
    if (shape == RoofShape::Flat) {
        notes.push_back(b.roof_inferred ? roof_shape_notes(shape).by_default : roof_shape_notes(shape).tagged);
        return;
    }

    RoofSpec spec = roof_spec(shape, tags, notes);
    const double height = roof_height(b, tags, spec, pitch, params, notes);
    if (height < kMinRoofHeight) {
        notes.push_back(ReportReason::RoofTooLow);
        return;
    }

    spec.eaves_z = b.height - height;
    spec.height = height;
    std::vector<RoofFace> faces;
    RoofShape built = shape;
    ReportReason why{};  // set by make_roof_faces when it fails
    if (!make_roof_faces(b.outer, b.holes, spec, &faces, &built, &why)) {
        notes.push_back(why);
        if (b.height_source == HeightSource::Levels) b.height -= height;
        return;
    }
    for (RoofFace& wall : gable_walls(b.outer, b.holes, faces, spec.eaves_z)) faces.push_back(std::move(wall));
    bool valid = true;
    for (const RoofFace& face : faces) valid = valid && roof_face_is_valid(face, b, spec.eaves_z, b.height);
    if (!valid) {
        notes.push_back(roof_shape_notes(shape).failed_checks.value());
        if (b.height_source == HeightSource::Levels) b.height -= height;
        return;
    }
    if (built != shape) notes.push_back(roof_shape_notes(shape).built_hipped.value());
    b.roof_shape = built;
    b.roof_height = height;
    b.roof_faces = std::move(faces);
    notes.push_back(b.roof_inferred ? roof_shape_notes(built).by_default : roof_shape_notes(built).tagged);
}

}  // namespace

const RoofShapeNotes& roof_shape_notes(RoofShape shape) {
    using R = ReportReason;
    static const RoofShapeNotes kNotes[kRoofShapeCount] = {  // in RoofShape order
        {R::RoofFlatTagged, R::RoofFlatDefault, std::nullopt, std::nullopt},
        {R::RoofSkillionTagged, R::RoofSkillionDefault, R::RoofSkillionFailedChecks, R::RoofSkillionBuiltHipped},
        {R::RoofGabledTagged, R::RoofGabledDefault, R::RoofGabledFailedChecks, R::RoofGabledBuiltHipped},
        {R::RoofHippedTagged, R::RoofHippedDefault, R::RoofHippedFailedChecks, std::nullopt},
        {R::RoofHalfHippedTagged, R::RoofHalfHippedDefault, R::RoofHalfHippedFailedChecks,
         R::RoofHalfHippedBuiltHipped},
        {R::RoofPyramidalTagged, R::RoofPyramidalDefault, R::RoofPyramidalFailedChecks, R::RoofPyramidalBuiltHipped},
        {R::RoofGambrelTagged, R::RoofGambrelDefault, R::RoofGambrelFailedChecks, R::RoofGambrelBuiltHipped},
        {R::RoofMansardTagged, R::RoofMansardDefault, R::RoofMansardFailedChecks, R::RoofMansardBuiltHipped},
        {R::RoofDomeTagged, R::RoofDomeDefault, R::RoofDomeFailedChecks, R::RoofDomeBuiltHipped},
        {R::RoofOnionTagged, R::RoofOnionDefault, R::RoofOnionFailedChecks, R::RoofOnionBuiltHipped},
        {R::RoofRoundTagged, R::RoofRoundDefault, R::RoofRoundFailedChecks, R::RoofRoundBuiltHipped},
    };
    return kNotes[static_cast<int>(shape)];
}

void build_roofs(std::vector<Building>& buildings, const BuildingTagIndex& index, const BuildingParams& params,
                 ParseReport& report, const RoofEvidence* given) {
    // Buildings are independent (the straight skeleton is most of the stage's time): in parallel,
    // with the notes counted afterwards in building order, so the report does not depend on threads.
    const RoofEvidence evidence = given ? *given : roof_evidence(buildings, index);
    std::vector<std::vector<ReportReason>> notes(buildings.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, buildings.size(), 64), [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) build_roof(buildings[i], index, evidence, params, notes[i]);
    });
    for (const auto& list : notes)
        for (ReportReason note : list) report.note(ReportKind::Roofs, note);
}

}  // namespace citygen
