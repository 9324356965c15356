// The farm's region statistics file (osmparse/tiles/region_statistics.h): it reads back exactly
// what was written, concatenated parts are their sum, and anything malformed, out of range or cut
// is refused with one line naming the file and the line.
#include <gtest/gtest.h>

#include <cmath>

#include "common/error.h"
#include "osmparse/tiles/region_statistics.h"

namespace citygen {
namespace {

RegionStatistics sample() {
    RegionStatistics s;
    s.heights.tagged = {{"yes", 0, 1.0 / 3.0}, {"shop house%\n\t", 4, 830}, {"Wohnhaus-ä", 2, 0.1}};
    s.heights.calibration = {{0, -0.1234567890123}, {3, 2.0 / 7.0}};
    s.roofs.tagged[1] = 12;
    s.roofs.pitched[1] = 7;
    s.roofs.tagged[5] = 3;
    return s;
}

void expect_equal(const RegionStatistics& a, const RegionStatistics& b) {
    ASSERT_EQ(a.heights.tagged.size(), b.heights.tagged.size());
    for (size_t i = 0; i < a.heights.tagged.size(); ++i) {
        EXPECT_EQ(a.heights.tagged[i].type, b.heights.tagged[i].type);
        EXPECT_EQ(a.heights.tagged[i].area_class, b.heights.tagged[i].area_class);
        EXPECT_EQ(a.heights.tagged[i].height, b.heights.tagged[i].height) << "to the bit";
    }
    ASSERT_EQ(a.heights.calibration.size(), b.heights.calibration.size());
    for (size_t i = 0; i < a.heights.calibration.size(); ++i) {
        EXPECT_EQ(a.heights.calibration[i].group, b.heights.calibration[i].group);
        EXPECT_EQ(a.heights.calibration[i].log_ratio, b.heights.calibration[i].log_ratio);
    }
    for (int g = 0; g < static_cast<int>(RoofGroup::Count); ++g) {
        EXPECT_EQ(a.roofs.tagged[g], b.roofs.tagged[g]) << g;
        EXPECT_EQ(a.roofs.pitched[g], b.roofs.pitched[g]) << g;
    }
}

TEST(RegionStatistics, ReadsBackExactlyWhatWasWritten) {
    const RegionStatistics s = sample();
    const std::string text = region_statistics_text(s);
    expect_equal(parse_region_statistics(text, "a.stats"), s);
    EXPECT_EQ(text.find('\t'), std::string::npos) << "types are escaped: one record a line";
    EXPECT_EQ(text.rfind("end 7\n"), text.size() - 6) << "three tagged, two ratios, two roof groups";
}

// Never a file its reader refuses: the extremes the gathering can meet read back.
TEST(RegionStatistics, TheExtremesReadBack) {
    RegionStatistics s;
    s.heights.tagged = {{std::string(1020, '\xe4'), 0, 5e-324}, {"yes", 4, 1000}};
    s.heights.calibration = {{1, std::log(4.9e-324)}, {2, std::log(1.7e308)}};  // the logs of the least and largest doubles
    s.roofs.tagged[0] = s.roofs.pitched[0] = 2147483647;
    expect_equal(parse_region_statistics(region_statistics_text(s), "x.stats"), s);
}

TEST(RegionStatistics, ConcatenatedPartsAreTheirSum) {
    const RegionStatistics a = sample();
    RegionStatistics b;
    b.heights.tagged = {{"apartments", 3, 24}};
    b.roofs.tagged[1] = 1;
    b.roofs.pitched[1] = 1;
    RegionStatistics sum = a;
    sum.heights.tagged.push_back(b.heights.tagged[0]);
    sum.roofs.tagged[1] += 1;
    sum.roofs.pitched[1] += 1;
    expect_equal(parse_region_statistics(region_statistics_text(a) + region_statistics_text(b), "ab.stats"), sum);
    // A tile with no tagged building writes an empty part, which adds nothing.
    expect_equal(parse_region_statistics(region_statistics_text({}) + region_statistics_text(a), "0a.stats"), a);
}

TEST(RegionStatistics, RefusesWhatIsMalformedOutOfRangeOrCut) {
    const std::string head = "citygen-region-statistics 1\n";
    const std::string whole = region_statistics_text(sample());
    const std::pair<std::string, std::string> cases[] = {
        {"", "empty"},
        {"tagged 0 0x1p+3 yes\nend 1\n", "line 1: expected"},
        {whole.substr(0, whole.size() - 6), "cut short"},
        {whole.substr(0, whole.size() / 2), ""},
        {whole + whole.substr(0, whole.size() / 2), ""},
        {head + "tagged 0 0x1p+3 yes\nend 2\n", "line 3: record count"},
        {head + "storeys 0 3\nend 1\n", "unknown record 'storeys'"},
        {head + "tagged 5 0x1p+3 yes\nend 1\n", "footprint class"},
        {head + "tagged -1 0x1p+3 yes\nend 1\n", "footprint class"},
        {head + "tagged 0 nan yes\nend 1\n", "height"},
        {head + "tagged 0 inf yes\nend 1\n", "height"},
        {head + "tagged 0 -3 yes\nend 1\n", "height"},
        {head + "tagged 0 0 yes\nend 1\n", "height 0"},
        {head + "tagged 0 1e9 yes\nend 1\n", "height"},
        {head + "tagged 0 12m yes\nend 1\n", "height"},
        {head + "tagged 0 12\nend 1\n", "too few fields"},
        {head + "tagged 0 12 yes no\nend 1\n", "unexpected field 'no'"},
        {head + "tagged 0 12 ye%G1\nend 1\n", "escape"},
        {head + "tagged 0 12 ye%4\nend 1\n", "escape"},
        {head + "tagged 0 12 " + std::string(1100, 'a') + "\nend 1\n", "type longer"},
        {head + "ratio 4 0.1\nend 1\n", "group"},
        {head + "ratio 0 1e4\nend 1\n", "ratio"},
        {head + "roofs 6 1 0\nend 1\n", "roof group"},
        {head + "roofs 1 2 3\nend 1\n", "pitched count"},
        {head + "roofs 1 -2 0\nend 1\n", "count"},
        {head + "roofs 1 2147483647 0\nroofs 1 1 0\nend 2\n", "roof counts beyond"},
        {head + head + "end 0\n", "opens before"},
        {"\x89PNG\r\n", "not a region statistics file"},
    };
    for (const auto& [text, message] : cases) {
        try {
            parse_region_statistics(text, "t.stats");
            ADD_FAILURE() << "accepted: " << text.substr(0, 80);
        } catch (const Error& e) {
            const std::string what = e.what();
            EXPECT_EQ(what.rfind("t.stats: ", 0), 0u) << what;
            EXPECT_NE(what.find(message), std::string::npos) << what << " (wanted " << message << ")";
            EXPECT_EQ(what.find('\n'), std::string::npos) << what;
        }
    }
}

TEST(RegionStatistics, AMissingFileIsNamed) {
    try {
        read_region_statistics({"/nonexistent/region.stats"});
        ADD_FAILURE();
    } catch (const Error& e) {
        EXPECT_NE(std::string(e.what()).find("/nonexistent/region.stats: cannot open"), std::string::npos) << e.what();
    }
}

}  // namespace
}  // namespace citygen
