#include "common/progress.h"

#include <cstdio>

namespace citygen {

namespace {
constexpr double kShowAfterSeconds = 1.0;   // short runs never show a bar
constexpr double kRedrawSeconds = 0.25;
}

Progress::Progress(std::string label, uint64_t total, bool quiet)
    : Progress(std::move(label), total, ProgressSettings{quiet, kShowAfterSeconds}) {}

Progress::Progress(std::string label, uint64_t total, const ProgressSettings& settings)
    : label_(std::move(label)), total_(total ? total : 1), quiet_(settings.quiet),
      show_after_seconds_(settings.show_after_seconds), start_(std::chrono::steady_clock::now()),
      last_draw_(start_) {}

Progress::~Progress() { finish(); }

void Progress::advance(uint64_t amount) {
    const uint64_t done = done_.fetch_add(amount) + amount;
    if (quiet_) return;
    const auto now = std::chrono::steady_clock::now();
    if (std::chrono::duration<double>(now - start_).count() < show_after_seconds_) return;
    std::unique_lock<std::mutex> lock(mutex_, std::try_to_lock);
    if (!lock.owns_lock() || finished_) return;
    if (std::chrono::duration<double>(now - last_draw_).count() < kRedrawSeconds) return;
    last_draw_ = now;
    draw(done, false);
}

void Progress::finish() {
    std::lock_guard<std::mutex> lock(mutex_);
    if (finished_) return;
    finished_ = true;
    // Work that ran long in few steps (never redrawn) still says how long it took.
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    if (shown_ || (!quiet_ && elapsed >= show_after_seconds_)) draw(total_, true);
}

void Progress::draw(uint64_t done, bool final) {
    shown_ = true;
    const double fraction = done >= total_ ? 1.0 : static_cast<double>(done) / total_;
    const double elapsed =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double eta = fraction > 0 ? elapsed * (1 - fraction) / fraction : 0;
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(fraction * kWidth);
    std::string bar(filled, '#');
    bar.resize(kWidth, '.');
    std::fprintf(stderr, "\r%s [%s] %5.1f%%  %s %.0fs ", label_.c_str(), bar.c_str(),
                 100 * fraction, final ? "took" : "ETA", final ? elapsed : eta);
    if (final) std::fputc('\n', stderr);
    std::fflush(stderr);
}

}  // namespace citygen
