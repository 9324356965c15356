#include "osmparse/run_stages.h"

#include <algorithm>
#include <chrono>
#include <set>

#include <tbb/task_group.h>

#include "common/error.h"

namespace citygen {

namespace {

bool contains(const std::vector<std::string>& parts, const std::string& part) {
    return std::find(parts.begin(), parts.end(), part) != parts.end();
}

// Whether `a` and `b` may run at the same time: neither touches what the other writes.
bool independent(const Stage& a, const Stage& b) {
    for (const std::string& w : a.writes)
        if (contains(b.reads, w) || contains(b.writes, w)) return false;
    for (const std::string& w : b.writes)
        if (contains(a.reads, w)) return false;
    return true;
}

double seconds_since(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Runs stage `i` into reports[i], adding its time to seconds[i].
void run_timed(const std::vector<Stage>& stages, size_t i, std::vector<ParseReport>& reports,
               std::vector<double>& seconds) {
    const auto start = std::chrono::steady_clock::now();
    stages[i].run(reports[i]);
    seconds[i] += seconds_since(start);
}

void run_together(const std::vector<Stage>& stages, const std::vector<size_t>& run, const StageHooks& hooks,
                  std::vector<ParseReport>& reports, std::vector<double>& seconds) {
    if (stages[run.front()].per_slice) {
        const size_t n = hooks.slice_count();
        for (size_t s = 0; s < n; ++s) {
            hooks.select_slice(s);
            for (size_t i : run) run_timed(stages, i, reports, seconds);
        }
        return;
    }
    tbb::task_group tasks;
    for (size_t k = 1; k < run.size(); ++k) tasks.run([&, k] { run_timed(stages, run[k], reports, seconds); });
    run_timed(stages, run.front(), reports, seconds);  // on this thread
    tasks.wait();
}

}  // namespace

std::map<std::string, size_t> last_readers(const std::vector<Stage>& stages) {
    std::map<std::string, size_t> last_writer, last_reader;
    for (size_t i = 0; i < stages.size(); ++i) {
        if (!stages[i].enabled) continue;
        for (const std::string& p : stages[i].writes) last_writer[p] = i;
        for (const std::string& p : stages[i].reads) last_reader[p] = i;
    }
    for (const auto& [part, i] : last_writer) last_reader.emplace(part, i);  // kept if read
    return last_reader;
}

std::vector<std::vector<size_t>> stage_runs(const std::vector<Stage>& stages) {
    std::vector<std::vector<size_t>> runs;
    for (size_t i = 0; i < stages.size(); ++i) {
        const Stage& s = stages[i];
        if (!s.enabled) continue;
        bool joins = !runs.empty() && stages[runs.back().front()].per_slice == s.per_slice;
        if (joins && !s.per_slice)
            for (size_t j : runs.back()) joins = joins && independent(stages[j], s);
        if (joins) {
            runs.back().push_back(i);
        } else {
            runs.push_back({i});
        }
    }
    return runs;
}

void check_parts(const std::vector<Stage>& stages) {
    std::set<std::string> written;
    for (const Stage& s : stages) {
        if (!s.enabled) continue;
        for (const std::string& p : s.reads)
            if (!written.count(p)) throw Error("stage '" + s.name + "' reads '" + p + "', which no stage before it writes");
        written.insert(s.writes.begin(), s.writes.end());
    }
}

void run_stages(const std::vector<Stage>& stages, const StageHooks& hooks, ParseReport& report) {
    check_parts(stages);
    const std::map<std::string, size_t> last = last_readers(stages);
    std::set<std::string> freed;
    for (const std::vector<size_t>& run : stage_runs(stages)) {
        std::vector<ParseReport> reports(stages.size());
        std::vector<double> seconds(stages.size(), 0.0);
        run_together(stages, run, hooks, reports, seconds);
        for (size_t i : run) {
            report.merge(reports[i]);
            report.stage_time(stages[i].name, seconds[i]);
        }
        for (const auto& [part, i] : last) {
            const auto f = hooks.free.find(part);
            if (i > run.back() || f == hooks.free.end() || !freed.insert(part).second) continue;
            f->second();
        }
    }
}

}  // namespace citygen
