// "Did you mean" (core/suggest.hpp): edit distances, and which known name, if any, is offered.
#include "core/suggest.hpp"
#include <gtest/gtest.h>

namespace test_suggest {

using namespace terrace;

TEST(Suggest, EditDistanceCountsEachEditOnce) {
    EXPECT_EQ(editDistance("", ""), 0);
    EXPECT_EQ(editDistance("abc", ""), 3);
    EXPECT_EQ(editDistance("", "abc"), 3);
    EXPECT_EQ(editDistance("kitten", "sitting"), 3);  // two substitutions and an insertion
    EXPECT_EQ(editDistance("density", "desnity"), 1); // one transposition, not two edits
    EXPECT_EQ(editDistance("dV", "dv"), 0);           // case is ignored
    EXPECT_EQ(editDistance("dt", "dt_fs"), 3);
    EXPECT_EQ(editDistance("ca", "abc"), 3); // optimal string alignment: no edit of a moved pair
    EXPECT_EQ(editDistance("smd", "dmd"), editDistance("dmd", "smd"));
}

TEST(Suggest, NearestNameIsOfferedOnlyWhenNearEnough) {
    const std::vector<std::string> smd = {"dt_fs", "skin", "scheme"};
    EXPECT_EQ(nearestName("dt", smd), "dt_fs");  // the unit suffix left off
    EXPECT_EQ(nearestName("skni", smd), "skin"); // a transposition
    EXPECT_EQ(nearestName("shceme", smd), "scheme");
    EXPECT_EQ(nearestName("bogus", smd), "");
    EXPECT_EQ(nearestName("dt_ps", smd), "dt_fs"); // the wrong unit
    const std::vector<std::string> state = {"n", "density", "temperature", "orientations"};
    EXPECT_EQ(nearestName("temp", state), "temperature"); // three letters and more begin a name
    EXPECT_EQ(nearestName("N", state), "n");
    EXPECT_EQ(nearestName("x", state), "");  // one letter is no evidence of any other
    EXPECT_EQ(nearestName("de", state), ""); // nor are two, unless a whole '_' part
    EXPECT_EQ(nearestName("densty", state), "density");
    // The nearest wins (a whole '_' part counts as no edit); between equals, the first listed.
    EXPECT_EQ(nearestName("ab", {"abc", "ab_x"}), "ab_x");
    EXPECT_EQ(nearestName("ab", {"abc", "abd"}), "abc");
    EXPECT_EQ(nearestName("sdm", {"dmd", "smd"}), "smd");
    EXPECT_EQ(nearestName("--strct", {"--out", "--strict", "--set"}), "--strict");
}

} // namespace test_suggest
