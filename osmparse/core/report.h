// The table osmparse prints at the end: per kind of object, how many were read, kept and
// dropped (by reason), then the time each stage took.
#pragma once

#include <cstdint>
#include <cstdio>
#include <map>
#include <string>
#include <utility>
#include <vector>

namespace citygen {

class ParseReport {
public:
    void read(const std::string& kind, int64_t n = 1) { row(kind).read += n; }
    void kept(const std::string& kind, int64_t n = 1) {
        Row& r = row(kind);
        r.kept += n;
        r.has_kept = true;
    }
    void dropped(const std::string& kind, const std::string& reason, int64_t n = 1) {
        row(kind).dropped[reason] += n;
    }
    // Not dropped, but changed or guessed (e.g. "height from random", "clipped at edge").
    void note(const std::string& kind, const std::string& what, int64_t n = 1) {
        row(kind).notes[what] += n;
    }
    void stage_time(const std::string& stage, double seconds) { times_.emplace_back(stage, seconds); }
    // Adds the counts and stage times of `other` as if they had been reported here, in its order.
    // Stages that run side by side report into reports of their own, merged in pipeline order,
    // so the printed report does not depend on the threads.
    void merge(const ParseReport& other);

    int64_t read_count(const std::string& kind) const;
    int64_t kept_count(const std::string& kind) const;
    int64_t dropped_count(const std::string& kind, const std::string& reason) const;
    int64_t note_count(const std::string& kind, const std::string& what) const;

    void print(std::FILE* out) const;

private:
    struct Row {
        int64_t read = 0, kept = 0;
        bool has_kept = false;  // rows of the read stage only count what they pass on
        std::map<std::string, int64_t> dropped, notes;
    };
    Row& row(const std::string& kind);
    std::vector<std::pair<std::string, Row>> rows_;  // in first-use order: pipeline order
    std::vector<std::pair<std::string, double>> times_;
};

}  // namespace citygen
