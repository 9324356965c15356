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
    r.read(ReportKind::Buildings, 3);
    r.dropped(ReportKind::Buildings, ReportReason::SliverBelowMinArea, 1);
    r.note(ReportKind::Buildings, ReportReason::Repaired);
    r.stage_time("first", 0.5);
}
void second_stage(ParseReport& r) {
    r.read(ReportKind::RoadWays, 2);
    r.kept(ReportKind::RoadWays, 2);
    r.kept(ReportKind::Buildings, 2);
    r.dropped(ReportKind::Buildings, ReportReason::SliverBelowMinArea, 0);  // an entry with nothing in it still prints
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
    EXPECT_EQ(merged.kept_count(ReportKind::Buildings), 2);
    EXPECT_EQ(merged.dropped_count(ReportKind::Buildings, ReportReason::SliverBelowMinArea), 1);
    EXPECT_EQ(merged.read_count(ReportKind::RoadWays), 2);
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
    EXPECT_LT(first.find("\nbuildings"), first.find("\nroad ways"));
    EXPECT_GT(second.find("\nbuildings"), second.find("\nroad ways"));
}

// Rows print in first-use order; under a row, reasons by their text, whatever the enum's order.
TEST(ParseReport, PrintsRowsInFirstUseOrderAndReasonsByText) {
    ParseReport r;
    r.dropped(ReportKind::RoadWays, ReportReason::InvalidLocation);
    r.dropped(ReportKind::RoadWays, ReportReason::Degenerate, 2);
    r.note(ReportKind::RoadWays, ReportReason::ZeroLength);
    r.note(ReportKind::RoadWays, ReportReason::AreaYes);
    r.read(ReportKind::Buildings);
    const std::string out = printed(r);
    const std::string expected_rows =
        "object                         read       kept    dropped\n"
        "road ways                         0          -          3\n"
        "    dropped        2  degenerate (fewer than 3 distinct points)\n"
        "    dropped        1  invalid location\n"
        "    note           1  area=yes\n"
        "    note           1  zero length\n"
        "buildings                         1          -          0\n";
    EXPECT_EQ(out.substr(0, expected_rows.size()), expected_rows);
}
