// End-to-end checks of comic_stereo_eval: help, a synthetic pair with known answers, bad input
// as one-line errors with non-zero exit codes, and the real Middlebury folders when present.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>

#include "io/core/file_utils.h"
#include "tests/frontend/synthetic_stereo_scene.h"
#include "tests/test_support.h"

namespace {

using comic::test::AppPath;
using comic::test::RunCommand;
using comic::test::ScopedTempDir;
using comic::test::SyntheticStereoScene;

// The synthetic pair as Middlebury-style files (disparity stored x4) in `dir`.
void WriteScene(const ScopedTempDir& dir) {
  const comic::io::MiddleburyPair scene = SyntheticStereoScene::Make();
  cv::Mat stored;
  scene.disparity.convertTo(stored, CV_8U, 4.0);
  cv::imwrite(dir.File("left.png"), scene.left_gray);
  cv::imwrite(dir.File("right.png"), scene.right_gray);
  cv::imwrite(dir.File("disp.png"), stored);
  cv::imwrite(dir.File("nonocc.png"), scene.nonocc);
  cv::imwrite(dir.File("disc.png"), scene.disc);
  cv::imwrite(dir.File("small.png"), cv::Mat(30, 40, CV_8UC1, cv::Scalar(9)));
}

std::string SceneArgs(const ScopedTempDir& dir) {
  return dir.File("left.png") + " " + dir.File("right.png") + " --disparity " +
         dir.File("disp.png") + " --nonocc " + dir.File("nonocc.png") + " --disc " +
         dir.File("disc.png");
}

nlohmann::json ReadJson(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

TEST(ComicStereoEval, HelpDocumentsEveryOption) {
  const auto result = RunCommand(AppPath("comic_stereo_eval") + " --help");
  EXPECT_EQ(result.exit_code, 0);
  for (const char* option : {"--disparity",
                             "--disparity-scale",
                             "--disc",
                             "--nonocc",
                             "--middlebury",
                             "--output",
                             "--resize-height",
                             "--methods",
                             "--counts",
                             "--count-reference",
                             "--max-cost",
                             "--sensitivity",
                             "--tolerance",
                             "--row-tolerance",
                             "--min-disparity",
                             "--max-disparity",
                             "--disparity-margin",
                             "--min-side-overlap",
                             "--repeatability",
                             "--precision-reference",
                             "--target-precision",
                             "--mser-merge-radius",
                             "--threads",
                             "--figure-methods",
                             "--quiet"}) {
    EXPECT_NE(result.output.find(option), std::string::npos) << option;
  }
}

TEST(ComicStereoEval, SyntheticPairGivesTheConstructedAnswers) {
  ScopedTempDir dir;
  WriteScene(dir);
  const std::string out = dir.File("out");
  const auto result =
      RunCommand(AppPath("comic_stereo_eval") + " " + SceneArgs(dir) +
                 " --disparity-scale 4 --resize-height 0 --methods harris/full,fast/full"
                 " --counts 60 --quiet --output " +
                 out);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_TRUE(result.output.empty()) << result.output;  // --quiet
  for (const char* file :
       {"stereo_eval.md", "stereo_eval.json", "protocol.csv", "pairs.csv", "detections.csv",
        "scores.csv", "matched_precision.csv", "repeatability.csv", "paper_comparison.csv"}) {
    EXPECT_TRUE(std::ifstream(out + "/" + file).good()) << file;
  }
  const nlohmann::json report = ReadJson(out + "/stereo_eval.json");
  ASSERT_EQ(report["pairs"].size(), 1u);
  EXPECT_DOUBLE_EQ(report["pairs"][0]["max GT disparity px"].get<double>(), 12.0);
  EXPECT_DOUBLE_EQ(report["pairs"][0]["gate max disparity px"].get<double>(), 13.5);
  int rows = 0;
  for (const auto& row : report["scores"]) {
    if (row["method"] != "harris/full" || row["T"] != "inf" || row["region"] != "overall") {
      continue;
    }
    ++rows;
    EXPECT_EQ(row["detected"].get<int>(), 60);
    EXPECT_GE(row["M_score(1) %"].get<double>(), 70.0);  // an exact shift matches well
  }
  EXPECT_EQ(rows, 1);
  // Not a paper pair: the comparison has no paper numbers.
  for (const auto& row : report["paper_comparison"]) EXPECT_TRUE(row["paper M_score %"].is_null());
  // The figure: CoMIC (not evaluated here) and Harris side by side, each the image's width.
  // The pair is named after the left image's folder.
  const cv::Mat figure = cv::imread(out + "/matches_" + comic::io::FileName(dir.path()) + ".png");
  ASSERT_FALSE(figure.empty());
  EXPECT_EQ(figure.cols, 2 * SyntheticStereoScene::kWidth);
  EXPECT_GT(figure.rows, SyntheticStereoScene::kHeight);  // plus a title bar
  // report.html (issue 28): the tables, the figure and the legend the PNG lacks, in one page.
  std::ifstream page_file(out + "/report.html");
  const std::string page((std::istreambuf_iterator<char>(page_file)), {});
  for (const char* text :
       {"comic_stereo_eval", "Matched precision", "Beside the paper", "harris/full",
        "M_score(1) (% of detected)", "data:image/", "correct match", "blue band"}) {
    EXPECT_NE(page.find(text), std::string::npos) << text;
  }
}

TEST(ComicStereoEval, OutputIsDeterministic) {
  ScopedTempDir dir;
  WriteScene(dir);
  const std::string command =
      AppPath("comic_stereo_eval") + " " + SceneArgs(dir) +
      " --disparity-scale 4 --resize-height 0 --methods harris,fast --counts 40 --quiet";
  ASSERT_EQ(RunCommand(command + " --output " + dir.File("a")).exit_code, 0);
  ASSERT_EQ(RunCommand(command + " --output " + dir.File("b")).exit_code, 0);
  for (const char* file : {"stereo_eval.json", "scores.csv", "stereo_eval.md"}) {
    std::ifstream a(dir.File("a") + "/" + file), b(dir.File("b") + "/" + file);
    const std::string ta((std::istreambuf_iterator<char>(a)), {});
    const std::string tb((std::istreambuf_iterator<char>(b)), {});
    EXPECT_FALSE(ta.empty()) << file;
    EXPECT_EQ(ta, tb) << file;
  }
}

TEST(ComicStereoEval, BadInputGivesOneLineErrorAndNonZeroExit) {
  ScopedTempDir dir;
  WriteScene(dir);
  const std::string out =
      " --output " + dir.File("out") + " --resize-height 0 --methods harris --quiet";
  const std::string left = dir.File("left.png");
  const std::string right = dir.File("right.png");
  const std::string disp = " --disparity " + dir.File("disp.png");
  struct Case {
    std::string args;
    int exit_code;
    std::string message;
  };
  const std::vector<Case> cases = {
      {left + " " + dir.File("small.png") + disp + " --disparity-scale 4", 1,
       "right image is 40x30"},
      {left + " " + right + " --disparity " + dir.File("small.png") + " --disparity-scale 4", 1,
       "disparity map is 40x30"},
      {left + " " + right + disp + " --disparity-scale 4 --disc " + dir.File("missing_disc.png"), 1,
       "missing_disc.png: no such file"},
      {left + " " + right + disp + " --disparity-scale 4 --nonocc " + dir.File("small.png"), 1,
       "nonocc mask is 40x30"},
      {left + " " + right + disp + " --disparity-scale 0", 2, "disparity scale must be > 0"},
      {left + " " + right + disp, 2, "--disparity-scale is required"},
      {left + " " + right + " --disparity-scale 4", 2, "missing --disparity"},
      {left + " " + right + disp + " --disparity-scale 4 --middlebury " + dir.path(), 2,
       "not both"},
      {"", 2, "missing input"},
      {"--middlebury " + dir.path(), 1, "no Middlebury pair found"},
      {"--middlebury " + dir.File("nowhere"), 1, "no such folder"},
      {left + " " + right + disp + " --disparity-scale 4 --methods sift", 2,
       "unknown detector 'sift'"},
      {left + " " + right + disp + " --disparity-scale 4 --max-cost 0", 2,
       "max_cost (T) must be > 0"},
      {left + " " + right + disp + " --disparity-scale 4 --counts 10,x", 2, "expected a number"},
      {left + " " + right + disp + " --disparity-scale 4 --output " + left, 2,
       "--output is the input LEFT"},
  };
  for (const Case& c : cases) {
    // The common options first, so a case's own options (given later) override them.
    const auto result = RunCommand(AppPath("comic_stereo_eval") + out + " " + c.args);
    EXPECT_EQ(result.exit_code, c.exit_code) << c.args << "\n" << result.output;
    EXPECT_NE(result.output.find(c.message), std::string::npos) << c.args << "\n" << result.output;
    EXPECT_EQ(comic::test::CountLines(result.output), 1) << c.args << "\n" << result.output;
  }
  // A Middlebury folder without its disc mask.
  ScopedTempDir folder;
  const comic::io::MiddleburyPair scene = SyntheticStereoScene::Make();
  cv::imwrite(folder.File("im2.png"), scene.left_gray);
  cv::imwrite(folder.File("im6.png"), scene.right_gray);
  cv::Mat stored;
  scene.disparity.convertTo(stored, CV_8U, 4.0);
  cv::imwrite(folder.File("groundtruth.png"), stored);
  cv::imwrite(folder.File("nonocc.png"), scene.nonocc);
  const auto result =
      RunCommand(AppPath("comic_stereo_eval") + " --middlebury " + folder.path() + out);
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("disc.png: no such file"), std::string::npos) << result.output;
  EXPECT_EQ(comic::test::CountLines(result.output), 1) << result.output;
  // Nothing was written for the failed runs.
  EXPECT_FALSE(std::ifstream(dir.File("out") + "/stereo_eval.json").good());
}

TEST(ComicStereoEval, MiddleburyFoldersWithThePapersNumbers) {
  COMIC_REQUIRE_SHARED_DATA();
  ScopedTempDir dir;
  const std::string data = comic::test::SharedDataDir();
  const auto result = RunCommand(
      AppPath("comic_stereo_eval") + " --middlebury " + data + "/middlebury2001_tsukuba," + data +
      "/middlebury2003_cones --methods harris/full,fast/full --counts 300 --quiet --output " +
      dir.path());
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json report = ReadJson(dir.File("stereo_eval.json"));
  ASSERT_EQ(report["pairs"].size(), 2u);
  EXPECT_EQ(report["pairs"][0]["height"].get<int>(), 700);
  EXPECT_NEAR(report["pairs"][1]["max GT disparity px"].get<double>(), 55 * 840.0 / 450.0, 1e-3);
  int harris_boundary_rows = 0;
  for (const auto& row : report["paper_comparison"]) {
    if (row["detector"] != "harris" || row["region"] != "boundary") continue;
    ++harris_boundary_rows;
    const double paper = row["paper M_score %"].get<double>();
    EXPECT_TRUE(paper == 20.9 || paper == 10.1) << paper;  // Tsukuba, Cones (Table 1)
  }
  EXPECT_EQ(harris_boundary_rows, 2);
  EXPECT_FALSE(cv::imread(dir.File("matches_middlebury2003_cones.png")).empty());
}

}  // namespace
