#include "io/report/number_text.h"

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace comic::io {
namespace {

TEST(NumberText, FormatsByThePrintfFormat) {
  EXPECT_EQ(NumberText("%.3g", 0.123456), "0.123");
  EXPECT_EQ(NumberText("%.1f %%", 42.25), "42.2 %");
  EXPECT_EQ(NumberText("%.0f", 1e6), "1000000");
  EXPECT_EQ(NumberText("%g", std::nan("")), "nan");
}

TEST(NumberText, CutsTextPastSixtyThreeCharacters) {
  const std::string text = NumberText("%.70f", 1.0);
  EXPECT_EQ(text.size(), 63u);
  EXPECT_EQ(text.substr(0, 4), "1.00");
}

}  // namespace
}  // namespace comic::io
