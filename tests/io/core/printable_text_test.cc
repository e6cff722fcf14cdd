#include "io/core/printable_text.h"

#include <gtest/gtest.h>

namespace comic::io {
namespace {

TEST(PrintableOneLine, KeepsPrintableTextAndJoinsLines) {
  EXPECT_EQ(PrintableOneLine("poses.txt: line 3: expected 12 numbers"),
            "poses.txt: line 3: expected 12 numbers");
  EXPECT_EQ(PrintableOneLine("libpng error: Read Error\nsecond line\r\n"),
            "libpng error: Read Error second line");
  EXPECT_EQ(PrintableOneLine("a\t\tb"), "a b");
  EXPECT_EQ(PrintableOneLine(""), "");
}

TEST(PrintableOneLine, EscapesBinaryBytes) {
  EXPECT_EQ(PrintableOneLine(std::string("x\x1b[31my\x01\xff", 9)), "x\\x1b[31my\\x01\\xff");
  EXPECT_EQ(PrintableOneLine(std::string("a\0b", 3)), "a\\x00b");
}

TEST(PrintableOneLine, CutsLongText) {
  const std::string cut = PrintableOneLine(std::string(1000, 'z'), 10);
  EXPECT_EQ(cut, std::string(10, 'z') + "...");
}

}  // namespace
}  // namespace comic::io
