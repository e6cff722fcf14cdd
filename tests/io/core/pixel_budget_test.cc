#include "io/core/pixel_budget.h"

#include <gtest/gtest.h>

#include "io/core/error.h"

namespace comic::io {
namespace {

TEST(PixelBudget, RefusesLargerImagesWithHowToRaiseIt) {
  EXPECT_NO_THROW(CheckPixelBudget("a.png", {100, 100}, 10000));
  try {
    CheckPixelBudget("big.png", {8000, 6000}, kDefaultMaxPixels);
    FAIL() << "no error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::kInvalidData);
    const std::string message = e.what();
    EXPECT_NE(message.find("big.png"), std::string::npos) << message;
    EXPECT_NE(message.find("8000x6000"), std::string::npos) << message;
    EXPECT_NE(message.find("--max-pixels 48000000"), std::string::npos) << message;
  }
}

TEST(PixelBudget, MaxPixelsHasADocumentedRange) {
  EXPECT_NO_THROW(CheckMaxPixels(1));
  EXPECT_NO_THROW(CheckMaxPixels(kDefaultMaxPixels));
  EXPECT_NO_THROW(CheckMaxPixels(kMaxMaxPixels));
  EXPECT_THROW(CheckMaxPixels(0), Error);
  EXPECT_THROW(CheckMaxPixels(kMaxMaxPixels + 1), Error);
}

}  // namespace
}  // namespace comic::io
