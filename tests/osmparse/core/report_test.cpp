// ParseReport::merge: stages that run side by side report into reports of their own; merged in
// pipeline order they must print what one report filled in that order prints.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "osmparse/core/report.h"

using namespace citygen;

namespace {

std::string printed(const ParseReport& report) {
    char* text = nullptr;
    size_t size = 0;
    std::FILE* memory = open_memstream(&text, &size);
    report.print(memory);
    std::fclose(memory);
    std::string out(text, size);
    std::free(text);
    return out;
}

// Two stages' worth of counts, the second adding to a row the first began.
void first_stage(ParseReport& r) {
    r.read("buildings", 3);
    r.dropped("buildings", "sliver", 1);
    r.note("buildings", "repaired");
    r.stage_time("first", 0.5);
}
void second_stage(ParseReport& r) {
    r.read("roads", 2);
    r.kept("roads", 2);
    r.kept("buildings", 2);
    r.dropped("buildings", "sliver", 0);  // a row entry with nothing in it still prints
    r.stage_time("second", 0.25);
}

}  // namespace

TEST(ParseReport, MergedReportsPrintLikeOneReportFilledInOrder) {
    ParseReport one;
    first_stage(one);
    second_stage(one);

    ParseReport merged, a, b;
    second_stage(b);  // filled in the "wrong" order, as threads may
    first_stage(a);
    merged.merge(a);
    merged.merge(b);
    EXPECT_EQ(printed(merged), printed(one));
    EXPECT_EQ(merged.kept_count("buildings"), 2);
    EXPECT_EQ(merged.dropped_count("buildings", "sliver"), 1);
    EXPECT_EQ(merged.read_count("roads"), 2);
}

TEST(ParseReport, MergeOrderDecidesTheRowOrder) {
    ParseReport a, b, ab, ba;
    first_stage(a);
    second_stage(b);
    ab.merge(a);
    ab.merge(b);
    ba.merge(b);
    ba.merge(a);
    const std::string first = printed(ab), second = printed(ba);
    EXPECT_LT(first.find("\nbuildings"), first.find("\nroads"));
    EXPECT_GT(second.find("\nbuildings"), second.find("\nroads"));
}
