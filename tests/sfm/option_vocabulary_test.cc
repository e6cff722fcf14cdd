#include "sfm/option_vocabulary.h"

#include <gtest/gtest.h>

#include <functional>
#include <string>

#include "frontend/matching/patch_matcher.h"
#include "io/core/error.h"

namespace comic::sfm {
namespace {

// The message a Check() gives, as each door shows it.
std::string Shown(const std::function<void()>& check) {
  try {
    check();
  } catch (const Error& e) {
    return WithUserOptionNames(e.what());
  }
  return "";
}

// Issue 29: a bad --search-radius was reported as "radius", the flag's name before its rename.
TEST(OptionVocabulary, ChecksNameTheOptionsUsersType) {
  frontend::PatchMatcherOptions matcher;
  matcher.radius = -1;
  EXPECT_EQ(Shown([&] { matcher.Check(); }).rfind("--search-radius must", 0), 0u);
  EXPECT_EQ(Shown([&] { matcher.Check(); }).find("matcher: radius"), std::string::npos);
  EXPECT_EQ(WithUserOptionNames("COLMAP export pair_window must be >= 1, got 0"),
            "--window must be >= 1, got 0");
  EXPECT_EQ(WithUserOptionNames("comic-paper: num_threads must be >= 0"), "--threads must be >= 0");
  EXPECT_EQ(WithUserOptionNames("comic: half_length must be >= 2"), "--half-length must be >= 2");
  EXPECT_EQ(WithUserOptionNames("first_frame must be >= 0, got -1"),
            "--first must be >= 0, got -1");
}

TEST(OptionVocabulary, LeavesOtherMessagesAlone) {
  for (const std::string message :
       {"a.png: no such file", "stride", "strides must be", "matcher: radiusx must be > 0", ""}) {
    EXPECT_EQ(WithUserOptionNames(message), message);
  }
}

}  // namespace
}  // namespace comic::sfm
