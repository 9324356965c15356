// The one table of report texts: every row and every reason has a text of its own, so no two
// print alike and none prints empty.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "osmparse/core/report_reasons.h"

using namespace citygen;

TEST(ReportReasons, EveryKindHasADistinctText) {
    std::set<std::string> seen;
    for (size_t i = 0; i < kReportKindCount; ++i) {
        const std::string text = text_of(static_cast<ReportKind>(i));
        EXPECT_FALSE(text.empty()) << "kind " << i;
        EXPECT_NE(text, "?") << "kind " << i;
        EXPECT_TRUE(seen.insert(text).second) << "kind " << i << " repeats \"" << text << "\"";
    }
    EXPECT_EQ(seen.size(), kReportKindCount);
}

TEST(ReportReasons, EveryReasonHasADistinctText) {
    std::set<std::string> seen;
    for (size_t i = 0; i < kReportReasonCount; ++i) {
        const std::string text = text_of(static_cast<ReportReason>(i));
        EXPECT_FALSE(text.empty()) << "reason " << i;
        EXPECT_NE(text, "?") << "reason " << i;
        EXPECT_TRUE(seen.insert(text).second) << "reason " << i << " repeats \"" << text << "\"";
    }
    EXPECT_EQ(seen.size(), kReportReasonCount);
}

TEST(ReportReasons, TextsAreTheReportsWords) {
    EXPECT_STREQ(text_of(ReportKind::BuildingParts), "building parts");
    EXPECT_STREQ(text_of(ReportKind::GeneratedBuildings), "generated buildings");
    EXPECT_STREQ(text_of(ReportReason::InvalidLocation), "invalid location");
    EXPECT_STREQ(text_of(ReportReason::LotOverlaps), "would overlap a road, sidewalk or building");
    EXPECT_STREQ(text_of(ReportKind::Count), "?");
    EXPECT_STREQ(text_of(ReportReason::Count), "?");
}
