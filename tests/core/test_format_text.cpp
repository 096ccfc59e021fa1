// printf into a string (core/format_text.hpp): the whole text, however long, and nothing more.
#include "core/format_text.hpp"
#include <gtest/gtest.h>
#include <string>

namespace test_format_text {

using namespace terrace;

TEST(FormatText, KeepsTheChosenPrecision) {
    EXPECT_EQ(formatText("%.3g", 2.0 / 3.0), "0.667");
    EXPECT_EQ(formatText("%s is %.2fx (%.2f-%.2f)", "SMD", 2.7, 2.3, 3.14159),
              "SMD is 2.70x (2.30-3.14)");
    EXPECT_EQ(formatText("%d %%", 5), "5 %");
}

TEST(FormatText, GivesTheWholeTextHoweverLong) {
    // The helpers it replaced cut verdicts at a fixed buffer (96, 160, 256 or 512 bytes).
    const std::string word(3000, 'x');
    const std::string text = formatText("[%s] %.1f", word.c_str(), 1.5);
    EXPECT_EQ(text.size(), 3000u + 6u);
    EXPECT_EQ(text, "[" + word + "] 1.5");
    EXPECT_EQ(text.find('\0'), std::string::npos);
}

TEST(FormatText, AnEmptyTextIsEmpty) {
    EXPECT_EQ(formatText("%s", ""), "");
}

} // namespace test_format_text
