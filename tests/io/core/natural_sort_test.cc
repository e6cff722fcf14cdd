#include "io/core/natural_sort.h"

#include <gtest/gtest.h>

namespace comic::io {
namespace {

TEST(NaturalSort, NumbersCompareByValue) {
  EXPECT_TRUE(NaturalLess("frame_2.png", "frame_10.png"));
  EXPECT_FALSE(NaturalLess("frame_10.png", "frame_2.png"));
  EXPECT_TRUE(NaturalLess("a9b", "a10a"));
  EXPECT_TRUE(NaturalLess("img99", "img100"));
}

TEST(NaturalSort, IsAStrictOrdering) {
  EXPECT_FALSE(NaturalLess("frame_7", "frame_7"));
  // Same value, different zero padding: ordered, never equal, never both ways.
  EXPECT_NE(NaturalLess("f1", "f01"), NaturalLess("f01", "f1"));
  EXPECT_TRUE(NaturalLess("abc", "abcd"));
  EXPECT_FALSE(NaturalLess("abcd", "abc"));
}

TEST(NaturalSort, SortsMixedNames) {
  std::vector<std::string> names = {"frame_10.png",  "frame_2.png",  "frame_1.png",
                                    "frame_100.png", "frame_20.png", "a.png"};
  NaturalSort(&names);
  const std::vector<std::string> expected = {"a.png",        "frame_1.png",  "frame_2.png",
                                             "frame_10.png", "frame_20.png", "frame_100.png"};
  EXPECT_EQ(names, expected);
}

TEST(NaturalSort, ZeroPaddedNamesKeepTheirOrder) {
  std::vector<std::string> names = {"000010.png", "000002.png", "000001.png"};
  NaturalSort(&names);
  EXPECT_EQ(names, (std::vector<std::string>{"000001.png", "000002.png", "000010.png"}));
}

TEST(NaturalSort, HugeDigitRunsDoNotOverflow) {
  EXPECT_TRUE(NaturalLess("x99999999999999999999999", "x100000000000000000000000"));
}

}  // namespace
}  // namespace comic::io
