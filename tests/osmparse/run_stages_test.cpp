// The stage runner on a made-up stage table: last readers, freeing, side by side, report order.
#include "osmparse/run_stages.h"

#include "common/error.h"

#include <atomic>
#include <chrono>
#include <mutex>
#include <thread>

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

using namespace citygen;

namespace {

// A writes a; B and C read it (independent: side by side); D reads b and c; E reads a and d;
// X, turned off, would read b last.
// Each stage logs what it finds alive, so a part freed too early or too late shows.
struct Table {
    std::mutex m;
    std::vector<std::string> log;
    std::map<std::string, bool> alive;
    std::atomic<int> running{0}, most_running{0};

    void note(const std::string& line) {
        std::lock_guard<std::mutex> lock(m);
        log.push_back(line);
    }
    bool is_alive(const std::string& part) {
        std::lock_guard<std::mutex> lock(m);
        return alive[part];
    }
    // Each stage counts under a report row of its own, so the printed report shows the merge order.
    static ReportKind row_of(const std::string& name) {
        const std::map<std::string, ReportKind> rows = {
            {"A", ReportKind::Buildings}, {"B", ReportKind::RoadWays},    {"C", ReportKind::PathWays},
            {"D", ReportKind::Roofs},     {"E", ReportKind::SeaPolygons}, {"X", ReportKind::ForestTrees},
        };
        return rows.at(name);
    }
    // Runs a stage body, counting how many run at the same time.
    std::function<void(ParseReport&)> stage(const std::string& name, std::vector<std::string> needs,
                                            std::vector<std::string> makes) {
        return [this, name, needs, makes](ParseReport& r) {
            const int now = ++running;
            for (int seen = most_running; now > seen && !most_running.compare_exchange_weak(seen, now);) {}
            for (const std::string& p : needs) EXPECT_TRUE(is_alive(p)) << name << " reads freed " << p;
            std::this_thread::sleep_for(std::chrono::milliseconds(50));  // long enough to overlap
            {
                std::lock_guard<std::mutex> lock(m);
                for (const std::string& p : makes) alive[p] = true;
            }
            r.read(row_of(name));
            note("ran " + name);
            --running;
        };
    }
    std::vector<Stage> stages() {
        return {
            {"A", {}, {"a"}, stage("A", {}, {"a"})},
            {"B", {"a"}, {"b"}, stage("B", {"a"}, {"b"})},
            {"C", {"a"}, {"c"}, stage("C", {"a"}, {"c"})},
            {"D", {"b", "c"}, {"d"}, stage("D", {"b", "c"}, {"d"})},
            {"E", {"a", "d"}, {"e"}, stage("E", {"a", "d"}, {"e"})},
            {"X", {"b"}, {"x"}, stage("X", {"b"}, {"x"}), false},
        };
    }
    StageHooks hooks() {
        StageHooks h;
        for (const char* p : {"a", "b", "c", "d"})
            h.free[p] = [this, p] {
                std::lock_guard<std::mutex> lock(m);
                alive[p] = false;
                log.push_back(std::string("free ") + p);
            };
        return h;
    }
};

TEST(RunStages, LastReadersComeFromTheTable) {
    Table t;
    const std::map<std::string, size_t> last = last_readers(t.stages());
    EXPECT_EQ(last.at("a"), 4u);  // E, not C
    EXPECT_EQ(last.at("b"), 3u);  // D: X is turned off
    EXPECT_EQ(last.at("c"), 3u);
    EXPECT_EQ(last.at("d"), 4u);
    EXPECT_EQ(last.at("e"), 4u);  // read by none: its writer
    EXPECT_EQ(last.count("x"), 0u);
}

TEST(RunStages, APartReadBeforeItIsWrittenIsAnError) {
    Table t;
    std::vector<Stage> stages = t.stages();
    EXPECT_NO_THROW(check_parts(stages));
    stages[3].reads.push_back("bb");  // misspelt
    EXPECT_THROW(check_parts(stages), Error);
    std::swap(stages[0], stages[1]);  // B before A: reads a before it is written
    stages[3].reads.pop_back();
    EXPECT_THROW(check_parts(stages), Error);
}

TEST(RunStages, IndependentConsecutiveStagesRunTogether) {
    Table t;
    const std::vector<std::vector<size_t>> runs = stage_runs(t.stages());
    // B and C read only a; D reads what they write; E what D writes.
    const std::vector<std::vector<size_t>> expected = {{0}, {1, 2}, {3}, {4}};
    EXPECT_EQ(runs, expected);
}

TEST(RunStages, FreesAfterTheLastReaderAndMergesInTableOrder) {
    for (int threads : {1, 2}) {
        Table t;
        ParseReport report;
        tbb::task_arena arena(threads);
        arena.execute([&] { run_stages(t.stages(), t.hooks(), report); });
        EXPECT_EQ(t.most_running.load(), threads) << "B and C side by side with two threads, not with one";
        // b and c once D is done, a and d once E is (A, B and C free nothing; B and C in any order).
        const std::vector<std::string> expected = {"ran D", "free b", "free c", "ran E", "free a", "free d"};
        std::vector<std::string> frees;
        for (const std::string& line : t.log)
            if (line != "ran A" && line != "ran B" && line != "ran C") frees.push_back(line);
        EXPECT_EQ(frees, expected) << threads << " threads";
        EXPECT_FALSE(t.alive["a"] || t.alive["b"] || t.alive["c"] || t.alive["d"]);
        EXPECT_TRUE(t.alive["e"]);  // a result: no way to free it
        char* text = nullptr;
        size_t size = 0;
        std::FILE* out = open_memstream(&text, &size);
        report.print(out);
        std::fclose(out);
        const std::string printed(text, size);
        std::free(text);
        size_t at = 0;
        for (const char* stage : {"A", "B", "C", "D", "E"}) {
            const char* row = text_of(Table::row_of(stage));
            const size_t found = printed.find(std::string("\n") + row + " ", at);
            EXPECT_NE(found, std::string::npos) << row << " in table order:\n" << printed;
            at = found;
        }
        EXPECT_EQ(printed.find(text_of(Table::row_of("X"))), std::string::npos);
    }
}

}  // namespace
