// End-to-end checks of comic_inspect: help, a real sequence, and bad input.
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>

#include "tests/test_support.h"

namespace {

using comic::test::AppPath;
using comic::test::RunCommand;

TEST(ComicInspect, HelpDocumentsEveryOption) {
  const auto result = RunCommand(AppPath("comic_inspect") + " --help");
  EXPECT_EQ(result.exit_code, 0);
  for (const char* option :
       {"--resize-height", "--first", "--last", "--stride", "--contact-sheet"}) {
    EXPECT_NE(result.output.find(option), std::string::npos) << option;
  }
}

TEST(ComicInspect, ReportsTheBundledExample) {
  comic::test::ScopedTempDir dir;
  const std::string sheet = dir.File("sheet.png");
  const auto result = RunCommand(AppPath("comic_inspect") + " " + comic::test::ExampleDir() +
                                 "/image_l --resize-height 185 --contact-sheet " + sheet);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("frames:      12"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("frame size:  613x185"), std::string::npos) << result.output;
  const cv::Mat image = cv::imread(sheet);
  ASSERT_FALSE(image.empty());
  EXPECT_EQ(image.rows, 160);
}

TEST(ComicInspect, BadInputGivesOneLineErrorAndNonZeroExit) {
  comic::test::ScopedTempDir dir;
  struct Case {
    std::string args;
    int exit_code;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"/nonexistent/frames", 1, "no such file or folder"},
      {dir.path(), 2, "folder holds no images"},
      {"", 2, "missing argument FRAMES"},
      {comic::test::ExampleDir() + "/image_l --stride 0", 2, "stride must be >= 1"},
      {comic::test::ExampleDir() + "/image_l --stride x", 2, "expected an integer"},
      {comic::test::ExampleDir() + "/image_l --bogus", 2, "unknown option --bogus"},
      {comic::test::ExampleDir() + "/image_l --contact-sheet /nonexistent/dir/sheet.png", 1,
       "does not exist"},
  };
  for (const Case& c : cases) {
    const auto result = RunCommand(AppPath("comic_inspect") + " " + c.args);
    EXPECT_EQ(result.exit_code, c.exit_code) << c.args << "\n" << result.output;
    EXPECT_NE(result.output.find(c.message), std::string::npos) << c.args << "\n" << result.output;
    EXPECT_EQ(comic::test::CountLines(result.output), 1) << result.output;
  }
}

}  // namespace
