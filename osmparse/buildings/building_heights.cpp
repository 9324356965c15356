#include "osmparse/buildings/building_heights.h"

#include <algorithm>
#include <cmath>
#include <optional>

#include "common/rng.h"
#include "osmparse/core/osm_units.h"

namespace citygen {

namespace {

// A height tag and the note that counts it when it is present but unusable.
struct HeightTag {
    const char* key;
    ReportReason bad;
};
constexpr HeightTag kHeight{"height", ReportReason::BadHeightTag};
constexpr HeightTag kLevels{"building:levels", ReportReason::BadLevelsTag};
constexpr HeightTag kMinHeight{"min_height", ReportReason::BadMinHeightTag};
constexpr HeightTag kMinLevel{"building:min_level", ReportReason::BadMinLevelTag};

// A length tag in [0, max_height], or nullopt (counted) when present but unusable.
std::optional<double> length_tag(const OsmTags& tags, HeightTag tag, double max_height, ParseReport& report,
                                 ReportKind kind) {
    const char* text = tags.get(tag.key);
    if (!text) return std::nullopt;
    std::optional<double> metres = parse_osm_length(text);
    if (!metres || *metres < 0 || *metres > max_height) {
        report.note(kind, tag.bad);
        return std::nullopt;
    }
    return metres;
}

// A level count whose height stays in [0, max_height], or nullopt (counted).
std::optional<double> levels_tag(const OsmTags& tags, HeightTag tag, const BuildingParams& params,
                                 ParseReport& report, ReportKind kind) {
    const char* text = tags.get(tag.key);
    if (!text) return std::nullopt;
    std::optional<double> levels = parse_osm_count(text);
    if (!levels || *levels * params.level_height > params.max_height) {
        report.note(kind, tag.bad);
        return std::nullopt;
    }
    return levels;
}

}  // namespace

BuildingHeight building_height(const OsmTags& tags, OsmRef ref, const BuildingParams& params,
                               ParseReport& report, ReportKind kind) {
    const std::optional<double> height = length_tag(tags, kHeight, params.max_height, report, kind);
    const std::optional<double> levels = levels_tag(tags, kLevels, params, report, kind);
    std::optional<double> min_height = length_tag(tags, kMinHeight, params.max_height, report, kind);
    const std::optional<double> min_level = levels_tag(tags, kMinLevel, params, report, kind);

    BuildingHeight out;
    if (height && *height > 0) {
        out.height = *height;
        out.source = HeightSource::Tagged;
    } else if (levels && *levels > 0) {
        out.height = *levels * params.level_height;
        out.source = HeightSource::Levels;
    } else {
        if (height || levels) report.note(kind, ReportReason::ZeroHeightIgnored);
        const double u = hash_to_unit(hash_keys(params.seed, static_cast<uint64_t>(ref.type),
                                                static_cast<uint64_t>(ref.id)));
        out.height = params.random_min_height + u * (params.random_max_height - params.random_min_height);
        out.source = HeightSource::Random;
    }
    report.note(kind, out.source == HeightSource::Tagged  ? ReportReason::HeightFromHeightTag
                      : out.source == HeightSource::Levels ? ReportReason::HeightFromLevels
                                                           : ReportReason::RandomHeight);

    if (!min_height && min_level) min_height = *min_level * params.level_height;
    if (min_height && *min_height >= out.height) {
        if (out.source == HeightSource::Random) {
            // Only the bottom is known: give the part one storey above it.
            out.height = *min_height + params.level_height;
        } else {
            report.note(kind, ReportReason::MinHeightNotBelowHeight);
            min_height.reset();
        }
    }
    out.min_height = min_height.value_or(0);

    // Storeys of this building or part: tagged levels above its bottom level, else as
    // many whole storeys as fit.
    if (levels && *levels > 0 && out.source != HeightSource::Random) {
        const double bottom_levels = min_level.value_or(out.min_height / params.level_height);
        out.levels = std::max(1, static_cast<int>(std::lround(*levels - bottom_levels)));
    } else {
        out.levels = std::max(1, static_cast<int>(std::lround((out.height - out.min_height) / params.level_height)));
    }
    return out;
}

}  // namespace citygen
