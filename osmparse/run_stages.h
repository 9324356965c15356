// The runner of a declared stage list (pipeline.cpp declares osmparse's): each stage names the
// parts of the parse it reads and writes; the runner runs the stages in table order, times each,
// frees each part after its last reader and runs consecutive independent stages side by side.
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "osmparse/core/report.h"

namespace citygen {

struct Stage {
    std::string name;                  // its row in the report's stage times
    std::vector<std::string> reads;    // the parts it reads
    std::vector<std::string> writes;   // the parts it writes (a part it changes is read and written)
    std::function<void(ParseReport&)> run;  // reports into the report given, not a shared one
    bool enabled = true;               // false: left out of the run (an option turned it off)
    // Consecutive per-slice stages run slice by slice (StageHooks::slices): each slice goes
    // through all of them before the next, so a slice can be finished and freed early.
    bool per_slice = false;
};

struct StageHooks {
    // How to free a part once its last reader is done; parts not named here are kept (the
    // results).
    std::map<std::string, std::function<void()>> free;
    // For per-slice stages: how many slices there are, and making slice i the current one.
    std::function<size_t()> slice_count;
    std::function<void(size_t)> select_slice;
};

// Per part, the index of the last enabled stage that reads it (or, if none reads it, that
// writes it): it can be freed after that stage.
std::map<std::string, size_t> last_readers(const std::vector<Stage>& stages);

// The stages in runs that run together: consecutive enabled stages of which none reads or
// writes a part another writes run side by side; per-slice stages form runs of their own.
std::vector<std::vector<size_t>> stage_runs(const std::vector<Stage>& stages);

// Throws Error if an enabled stage reads a part no enabled stage before it writes (a misspelt
// or misplaced part would otherwise be freed at the wrong time).
void check_parts(const std::vector<Stage>& stages);

// Runs the stages (after check_parts): each into a report of its own, merged into `report` in table order with its
// time, so the report does not depend on which stages ran side by side.
void run_stages(const std::vector<Stage>& stages, const StageHooks& hooks, ParseReport& report);

}  // namespace citygen
