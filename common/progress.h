// A progress bar with percentage and ETA on stderr, for long work. Silent when quiet,
// and it only appears once the work has run for a moment, so short runs stay clean.
#pragma once

#include <atomic>
#include <chrono>
#include <mutex>
#include <string>

namespace citygen {

// Whether and when work reports: never when quiet; otherwise once it has run show_after_seconds.
struct ProgressSettings {
    bool quiet = true;
    double show_after_seconds = 1.0;
};

class Progress {
public:
    Progress(std::string label, uint64_t total, bool quiet);
    Progress(std::string label, uint64_t total, const ProgressSettings& settings);
    ~Progress();
    // Thread-safe; redraws at most a few times a second.
    void advance(uint64_t amount = 1);
    void finish();

private:
    void draw(uint64_t done, bool final);
    std::string label_;
    uint64_t total_;
    bool quiet_;
    double show_after_seconds_;
    std::atomic<uint64_t> done_{0};
    std::chrono::steady_clock::time_point start_, last_draw_;
    std::mutex mutex_;
    bool shown_ = false, finished_ = false;
};

}  // namespace citygen
