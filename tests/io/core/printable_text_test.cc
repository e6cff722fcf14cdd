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

// Issue 29: a frame named in UTF-8 reads as the user typed it; what is not UTF-8, or would move
// the cursor or reorder the line, is still escaped.
TEST(PrintableOneLine, KeepsWellFormedUtf8AndEscapesTheRest) {
  EXPECT_EQ(PrintableOneLine("stra\xc3\x9f"
                             "e/\xe5\xb8\xa7 001.png \xf0\x9f\x93\xb7"),
            "stra\xc3\x9f"
            "e/\xe5\xb8\xa7 001.png \xf0\x9f\x93\xb7");
  // A lone continuation byte, a truncated sequence, an overlong '/', a surrogate.
  EXPECT_EQ(PrintableOneLine("a\x80"
                             "b"),
            "a\\x80b");
  EXPECT_EQ(PrintableOneLine("a\xc3"), "a\\xc3");
  EXPECT_EQ(PrintableOneLine("\xc0\xaf"), "\\xc0\\xaf");
  EXPECT_EQ(PrintableOneLine("\xed\xa0\x80"), "\\xed\\xa0\\x80");
  // C1 control U+009B (a terminal's CSI), right-to-left override U+202E, line separator U+2028.
  EXPECT_EQ(PrintableOneLine("\xc2\x9b"
                             "2J"),
            "\\xc2\\x9b2J");
  EXPECT_EQ(PrintableOneLine("\xe2\x80\xae"), "\\xe2\\x80\\xae");
  EXPECT_EQ(PrintableOneLine("\xe2\x80\xa8"), "\\xe2\\x80\\xa8");
}

// A name holding a tab or a line break reads unambiguously in a message: "a\tb.png" is not the
// file "a b.png". The line break that ends a message is no part of it.
TEST(PrintableMessage, EscapesTabsAndLineBreaksLikeOtherControlBytes) {
  EXPECT_EQ(PrintableMessage("a\tb.png: no such file"), "a\\x09b.png: no such file");
  EXPECT_EQ(PrintableMessage("x\ny\rz.png"), "x\\x0ay\\x0dz.png");
  EXPECT_EQ(PrintableMessage(std::string("x\x1b[31my\x01\xff", 9)), "x\\x1b[31my\\x01\\xff");
  EXPECT_EQ(PrintableMessage("one line\n"), "one line");
  EXPECT_EQ(PrintableMessage("stra\xc3\x9f"
                             "e.png"),
            "stra\xc3\x9f"
            "e.png");
  EXPECT_EQ(PrintableMessage(std::string(1000, 'z'), 10), std::string(10, 'z') + "...");
}

TEST(PrintableOneLine, CutsLongText) {
  const std::string cut = PrintableOneLine(std::string(1000, 'z'), 10);
  EXPECT_EQ(cut, std::string(10, 'z') + "...");
}

}  // namespace
}  // namespace comic::io
