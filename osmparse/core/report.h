// The table osmparse prints at the end: per kind of object, how many were read, kept and
// dropped (by reason), then the time each stage took.
#pragma once

#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "osmparse/core/report_reasons.h"

namespace citygen {

class ParseReport {
public:
    void read(ReportKind kind, int64_t n = 1) { row(kind).read += n; }
    void kept(ReportKind kind, int64_t n = 1) {
        Row& r = row(kind);
        r.kept += n;
        r.has_kept = true;
    }
    void dropped(ReportKind kind, ReportReason reason, int64_t n = 1) { row(kind).dropped[reason] += n; }
    // Not dropped, but changed or guessed (e.g. ReportReason::RandomHeight, ClippedAtEdge).
    void note(ReportKind kind, ReportReason what, int64_t n = 1) { row(kind).notes[what] += n; }
    void stage_time(const std::string& stage, double seconds) { times_.emplace_back(stage, seconds); }
    // Adds the counts and stage times of `other` as if they had been reported here, in its order.
    // Stages that run side by side report into reports of their own, merged in pipeline order,
    // so the printed report does not depend on the threads.
    void merge(const ParseReport& other);

    int64_t read_count(ReportKind kind) const;
    int64_t kept_count(ReportKind kind) const;
    int64_t dropped_count(ReportKind kind, ReportReason reason) const;
    int64_t note_count(ReportKind kind, ReportReason what) const;

    // Rows in first-use order; under each, its reasons by their text (alphabetical).
    void print(std::FILE* out) const;

private:
    struct Row {
        int64_t read = 0, kept = 0;
        bool has_kept = false;  // rows of the read stage only count what they pass on
        std::map<ReportReason, int64_t> dropped, notes;
    };
    Row& row(ReportKind kind);
    std::vector<std::pair<ReportKind, Row>> rows_;  // in first-use order: pipeline order
    std::vector<std::pair<std::string, double>> times_;
};

}  // namespace citygen
