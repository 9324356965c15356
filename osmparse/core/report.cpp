#include "osmparse/core/report.h"

#include <algorithm>
#include <cstring>

namespace citygen {

ParseReport::Row& ParseReport::row(ReportKind kind) {
    for (auto& [k, r] : rows_)
        if (k == kind) return r;
    rows_.emplace_back(kind, Row{});
    return rows_.back().second;
}

void ParseReport::merge(const ParseReport& other) {
    for (const auto& [kind, theirs] : other.rows_) {
        Row& mine = row(kind);
        mine.read += theirs.read;
        mine.kept += theirs.kept;
        mine.has_kept = mine.has_kept || theirs.has_kept;
        for (const auto& [reason, n] : theirs.dropped) mine.dropped[reason] += n;
        for (const auto& [what, n] : theirs.notes) mine.notes[what] += n;
    }
    times_.insert(times_.end(), other.times_.begin(), other.times_.end());
}

namespace {
template <typename Rows>
const auto* find_row(const Rows& rows, ReportKind kind) {
    for (const auto& entry : rows)
        if (entry.first == kind) return &entry.second;
    return static_cast<decltype(&rows.front().second)>(nullptr);
}
int64_t lookup(const std::map<ReportReason, int64_t>& m, ReportReason key) {
    auto it = m.find(key);
    return it == m.end() ? 0 : it->second;
}

// The reasons by their text, as the report always printed them.
std::vector<std::pair<ReportReason, int64_t>> by_text(const std::map<ReportReason, int64_t>& m) {
    std::vector<std::pair<ReportReason, int64_t>> out(m.begin(), m.end());
    std::sort(out.begin(), out.end(),
              [](const auto& a, const auto& b) { return std::strcmp(text_of(a.first), text_of(b.first)) < 0; });
    return out;
}
}  // namespace

int64_t ParseReport::read_count(ReportKind kind) const {
    const auto* r = find_row(rows_, kind);
    return r ? r->read : 0;
}
int64_t ParseReport::kept_count(ReportKind kind) const {
    const auto* r = find_row(rows_, kind);
    return r ? r->kept : 0;
}
int64_t ParseReport::dropped_count(ReportKind kind, ReportReason reason) const {
    const auto* r = find_row(rows_, kind);
    return r ? lookup(r->dropped, reason) : 0;
}
int64_t ParseReport::note_count(ReportKind kind, ReportReason what) const {
    const auto* r = find_row(rows_, kind);
    return r ? lookup(r->notes, what) : 0;
}

void ParseReport::print(std::FILE* out) const {
    std::fprintf(out, "%-24s %10s %10s %10s\n", "object", "read", "kept", "dropped");
    for (const auto& [kind, r] : rows_) {
        int64_t dropped = 0;
        for (const auto& entry : r.dropped) dropped += entry.second;
        char kept[32] = "-";
        if (r.has_kept) std::snprintf(kept, sizeof kept, "%lld", static_cast<long long>(r.kept));
        std::fprintf(out, "%-24s %10lld %10s %10lld\n", text_of(kind), static_cast<long long>(r.read), kept,
                     static_cast<long long>(dropped));
        for (const auto& [reason, n] : by_text(r.dropped))
            std::fprintf(out, "    dropped %8lld  %s\n", static_cast<long long>(n), text_of(reason));
        for (const auto& [what, n] : by_text(r.notes))
            std::fprintf(out, "    note    %8lld  %s\n", static_cast<long long>(n), text_of(what));
    }
    double total = 0;
    std::fprintf(out, "%-24s %10s\n", "stage", "seconds");
    for (const auto& [stage, s] : times_) {
        std::fprintf(out, "%-24s %10.3f\n", stage.c_str(), s);
        total += s;
    }
    // Stages that ran side by side (pipeline.cpp) each count their own time, so the sum can
    // exceed the run's wall time.
    std::fprintf(out, "%-24s %10.3f\n", "sum of stages", total);
}

}  // namespace citygen
