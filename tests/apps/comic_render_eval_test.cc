// comic_render_eval end to end: help, a short rendered street judged for one detector (the
// tables written, the numbers sane), and bad input failing with one line before any work.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "io/core/file_utils.h"
#include "tests/test_support.h"

namespace {

using comic::test::AppPath;
using comic::test::RunCommand;
using comic::test::ScopedTempDir;

TEST(ComicRenderEval, HelpDocumentsEveryOption) {
  const auto result = RunCommand(AppPath("comic_render_eval") + " --help");
  EXPECT_EQ(result.exit_code, 0);
  for (const char* option : {"--detectors", "--first", "--last", "--stride", "--matching",
                             "--follow-tolerance", "--boundary-band", "--min-track-length",
                             "--no-remap", "--threads", "--output", "--quiet"}) {
    EXPECT_NE(result.output.find(option), std::string::npos) << option;
  }
}

TEST(ComicRenderEval, JudgesTheTracksOfARenderedStreet) {
  ScopedTempDir dir;
  const auto render = RunCommand(AppPath("comic_render") + " " + comic::test::SourceDir() +
                                 "/scenes/test_street.json --photos " + comic::test::ExampleDir() +
                                 "/image_l --frames 8 -q -o " + dir.File("street"));
  ASSERT_EQ(render.exit_code, 0) << render.output;
  const auto eval = RunCommand(AppPath("comic_render_eval") + " " + dir.File("street") +
                               " --detectors harris --no-remap -q -o " + dir.File("eval"));
  ASSERT_EQ(eval.exit_code, 0) << eval.output;
  EXPECT_NE(eval.output.find("| harris"), std::string::npos) << eval.output;
  for (const char* file :
       {"boundary_benchmark.md", "boundary_benchmark.csv", "tracks_harris.csv"}) {
    EXPECT_TRUE(comic::io::PathExists(dir.File("eval/") + file)) << file;
  }
  const nlohmann::json json =
      nlohmann::json::parse(comic::io::ReadFileToString(dir.File("eval/boundary_benchmark.json")));
  const nlohmann::json& run = json["runs"][0];
  EXPECT_EQ(run["model"]["registered"], 8);
  EXPECT_GT(run["boundary_features"].get<int>(), 0);
  EXPECT_GT(run["other_tracks"]["following_fraction"].get<double>(), 0.5);
  EXPECT_FALSE(run.contains("without_boundary_tracks"));  // --no-remap
  EXPECT_FALSE(run.contains("without_labelled_sliding_tracks"));
  EXPECT_GT(run["labelled_sliding"]["labelled"].get<int>(), 0);
}

TEST(ComicRenderEval, BadInputGivesOneLineAndWritesNothing) {
  ScopedTempDir dir;
  comic::io::EnsureWritableDirectory(dir.File("frames_only/images"));
  struct Case {
    std::string args;
    int exit_code;
    std::string message;
  };
  const std::vector<Case> cases = {
      {dir.File("none"), 1, "no such folder"},
      {dir.File("frames_only"), 1, "--frames-only"},
      {dir.File("none") + " --detectors sift", 2, "sift"},
      {dir.File("none") + " --follow-tolerance 0", 2, "follow tolerance"},
  };
  for (const Case& c : cases) {
    const auto result =
        RunCommand(AppPath("comic_render_eval") + " " + c.args + " -o " + dir.File("out"));
    EXPECT_EQ(result.exit_code, c.exit_code) << c.args << "\n" << result.output;
    EXPECT_NE(result.output.find(c.message), std::string::npos) << c.args << "\n" << result.output;
    EXPECT_EQ(comic::test::CountLines(result.output), 1) << result.output;
    EXPECT_FALSE(comic::io::PathExists(dir.File("out")));
  }
}

}  // namespace
