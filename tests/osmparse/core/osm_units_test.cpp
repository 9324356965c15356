#include <gtest/gtest.h>

#include "osmparse/core/osm_units.h"

using citygen::parse_osm_count;
using citygen::parse_osm_length;

TEST(OsmUnits, PlainAndMetres) {
    EXPECT_DOUBLE_EQ(*parse_osm_length("12"), 12);
    EXPECT_DOUBLE_EQ(*parse_osm_length("12.5"), 12.5);
    EXPECT_DOUBLE_EQ(*parse_osm_length(" 12 m "), 12);
    EXPECT_DOUBLE_EQ(*parse_osm_length("12m"), 12);
    EXPECT_DOUBLE_EQ(*parse_osm_length("3,5"), 3.5);
    EXPECT_DOUBLE_EQ(*parse_osm_length("250 cm"), 2.5);
}

TEST(OsmUnits, FeetAndInches) {
    EXPECT_NEAR(*parse_osm_length("40 ft"), 12.192, 1e-9);
    EXPECT_NEAR(*parse_osm_length("40ft"), 12.192, 1e-9);
    EXPECT_NEAR(*parse_osm_length("40'"), 12.192, 1e-9);
    EXPECT_NEAR(*parse_osm_length("12'6\""), 12 * 0.3048 + 6 * 0.0254, 1e-9);
    EXPECT_NEAR(*parse_osm_length("10\""), 0.254, 1e-9);
}

// "ft" and a letter is not "feet": the reader once took it for "feet" and stepped past the
// string's end (found by cli_values_fuzz). The second NUL is where it then stopped.
TEST(OsmUnits, FtFollowedByALetterIsNotFeet) {
    const char text[] = {'3', 'f', 't', 'e', '\0', '\0'};
    EXPECT_FALSE(parse_osm_length(text).has_value());
    EXPECT_NEAR(*parse_osm_length("3 feet"), 0.9144, 1e-9);
}

TEST(OsmUnits, RejectsGarbage) {
    for (const char* bad : {"", "tall", "-5", "3;4", "12 parsecs", "nan", "inf", "1.2.3", "12'x", "5 mi"})
        EXPECT_FALSE(parse_osm_length(bad).has_value()) << bad;
    EXPECT_FALSE(parse_osm_length(nullptr).has_value());
}

TEST(OsmUnits, Counts) {
    EXPECT_DOUBLE_EQ(*parse_osm_count("4"), 4);
    EXPECT_DOUBLE_EQ(*parse_osm_count("2.5"), 2.5);
    EXPECT_FALSE(parse_osm_count("four").has_value());
    EXPECT_FALSE(parse_osm_count("-1").has_value());
    EXPECT_FALSE(parse_osm_count("2 m").has_value());
}
