// End-to-end checks of comic_track_eval: help, a synthetic sequence with masks and with boxes,
// the bundled KITTI clip with poses, and bad input.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <sstream>

#include "tests/test_support.h"

namespace {

using comic::test::AppPath;
using comic::test::RunCommand;
using comic::test::ScopedTempDir;

std::string ReadText(const std::string& path) {
  std::ifstream in(path);
  std::stringstream buffer;
  buffer << in.rdbuf();
  return buffer.str();
}

cv::Mat Texture(cv::Size size, uint64_t seed) {
  cv::Mat noise(size, CV_32F);
  cv::RNG rng(seed);
  rng.fill(noise, cv::RNG::NORMAL, 0, 1);
  cv::GaussianBlur(noise, noise, cv::Size(), 2.0);
  cv::Mat out;
  cv::normalize(noise, out, 20, 235, cv::NORM_MINMAX, CV_8U);
  return out;
}

// Eight 200x150 frames: a textured 60x50 object moving right by 3 px per frame over a textured
// background; frames/, masks/ (0/255 PNG) and boxes.txt (OTB, 1-based) under `dir`.
void WriteSyntheticSequence(const std::string& dir, int frames = 8) {
  std::filesystem::create_directories(dir + "/frames");
  std::filesystem::create_directories(dir + "/masks");
  const cv::Mat background = Texture({200, 150}, 1);
  const cv::Mat object = Texture({60, 50}, 2);
  std::ofstream boxes(dir + "/boxes.txt");
  for (int i = 0; i < frames; ++i) {
    cv::Mat frame = background.clone();
    const cv::Rect box(50 + 3 * i, 50, 60, 50);
    object.copyTo(frame(box));
    cv::Mat mask(frame.size(), CV_8UC1, cv::Scalar(0));
    mask(box).setTo(255);
    char name[32];
    std::snprintf(name, sizeof(name), "%03d.png", i);
    cv::imwrite(dir + "/frames/" + name, frame);
    cv::imwrite(dir + "/masks/" + name, mask);
    boxes << box.x + 1 << "\t" << box.y + 1 << "\t" << box.width << "\t" << box.height << "\n";
  }
}

const std::string kFastArgs =
    " --resize-height 0 --detectors harris,hessian,fast --count 15 --n 5 --frame-step 1";

TEST(ComicTrackEval, HelpDocumentsEveryOption) {
  const auto result = RunCommand(AppPath("comic_track_eval") + " --help");
  EXPECT_EQ(result.exit_code, 0);
  for (const char* option : {"--masks",
                             "--regions",
                             "--region-format",
                             "--detectors",
                             "--comic-matchers",
                             "--n",
                             "--frame-step",
                             "--count",
                             "--resize-height",
                             "--first",
                             "--last",
                             "--search-radius",
                             "--max-cost",
                             "--min-side-overlap",
                             "--boundary-band",
                             "--poses",
                             "--calib",
                             "--epipolar-tolerance",
                             "--target-precision",
                             "--overlay-frames",
                             "--threads",
                             "--output"}) {
    EXPECT_NE(result.output.find(option), std::string::npos) << option;
  }
}

TEST(ComicTrackEval, WritesTheTablesChartsAndOverlaysWithMasks) {
  ScopedTempDir dir;
  WriteSyntheticSequence(dir.path());
  const std::string out = dir.File("out");
  const auto result =
      RunCommand(AppPath("comic_track_eval") + " " + dir.File("frames") + " --masks " +
                 dir.File("masks") + kFastArgs + " --overlay-frames 2 --output " + out);
  ASSERT_EQ(result.exit_code, 0) << result.output;
  for (const char* file :
       {"scores_n5.md", "scores_n5.csv", "scores_n5.json", "scores_n5.png", "scores_n1.md",
        "scores_n1.csv", "scores_n1.json", "scores_n1.png", "threshold_sweep_n5.md",
        "threshold_sweep_n5.csv", "threshold_sweep_n5.json", "evaluation.json", "report.md"}) {
    EXPECT_TRUE(std::filesystem::exists(out + "/" + file)) << file;
  }
  int overlays = 0;
  for (const auto& entry : std::filesystem::directory_iterator(out)) {
    overlays += entry.path().filename().string().rfind("tracks_", 0) == 0 ? 1 : 0;
  }
  EXPECT_EQ(overlays, 2);
  EXPECT_FALSE(cv::imread(out + "/scores_n5.png").empty());

  const nlohmann::json table = nlohmann::json::parse(ReadText(out + "/scores_n5.json"));
  ASSERT_EQ(table.size(), 3u);
  EXPECT_EQ(table[0]["detector"], "harris");
  for (const auto& row : table) {
    // Equalised to 15 features on the object in frame 0 (float responses: no ties, except FAST's
    // integer scores, which may land a few away).
    if (row["detector"] != "fast") {
      EXPECT_EQ(row["N_0"], 15);
    }
    // A rigid textured object translating 3 px per frame is tracked through 5 frames.
    EXPECT_GT(row["M_score(5) % overall"].get<double>(), 30.0) << row.dump();
    EXPECT_LE(row["M_score(5) % overall"].get<double>(), 100.0);
  }
  const nlohmann::json evaluation = nlohmann::json::parse(ReadText(out + "/evaluation.json"));
  EXPECT_EQ(evaluation["reference_count"], 15);
  EXPECT_EQ(evaluation["rows"][0]["scores"][1]["samples (detections/residual: boundary, "
                                               "non-boundary, overall)"]
                .size(),
            3u);  // start frames 0, 1, 2 with n = 5 over 8 frames
  EXPECT_NE(ReadText(out + "/report.md").find("comic_track_eval"), std::string::npos);
  // report.html (issue 28): every table and chart, the overlays and their legend in one page.
  const std::string page = ReadText(out + "/report.html");
  for (const char* text : {"Scores, n = 5", "Scores, n = 1", "At other SSD thresholds T, n = 5",
                           "M_score(5) (% of N)", "ResM_5 (features)", "Tracks on frames",
                           "data:image/", "on the object's boundary", "outline"}) {
    EXPECT_NE(page.find(text), std::string::npos) << text;
  }
  // The sweep: one line per row and threshold; M_score grows with T, and the line at T = 400
  // is the main table's.
  const nlohmann::json sweep = nlohmann::json::parse(ReadText(out + "/threshold_sweep_n5.json"));
  ASSERT_EQ(sweep.size(), 3u * 6u);
  for (size_t r = 0; r < 3; ++r) {
    for (size_t t = 1; t < 6; ++t) {
      EXPECT_GE(sweep[r * 6 + t]["M_score(5) % overall"].get<double>(),
                sweep[r * 6 + t - 1]["M_score(5) % overall"].get<double>() - 1e-9);
    }
    EXPECT_EQ(sweep[r * 6 + 2]["T"], 400.0);
    EXPECT_DOUBLE_EQ(sweep[r * 6 + 2]["M_score(5) % overall"].get<double>(),
                     table[r]["M_score(5) % overall"].get<double>());
  }
  EXPECT_TRUE(sweep[5]["T"].is_null());  // infinity
  EXPECT_NE(result.output.find("frame 8/8"), std::string::npos) << result.output;
  // Issue 17: a line per frame with the time elapsed and an estimate of what remains.
  EXPECT_NE(result.output.find("detection and tracking: frame 1/8, "), std::string::npos)
      << result.output;
  EXPECT_NE(result.output.find(" s left"), std::string::npos) << result.output;
}

TEST(ComicTrackEval, BoxesGiveTheSameRegionAsMasksOfTheBox) {
  ScopedTempDir dir;
  WriteSyntheticSequence(dir.path());
  const std::string base = AppPath("comic_track_eval") + " " + dir.File("frames") + kFastArgs +
                           " --overlay-frames 0 --output ";
  ASSERT_EQ(RunCommand(base + dir.File("m") + " --masks " + dir.File("masks")).exit_code, 0);
  const auto boxes = RunCommand(base + dir.File("b") + " --regions " + dir.File("boxes.txt"));
  ASSERT_EQ(boxes.exit_code, 0) << boxes.output;
  EXPECT_EQ(ReadText(dir.File("m") + "/scores_n5.csv"), ReadText(dir.File("b") + "/scores_n5.csv"));
}

// The equal-count precision table (two matchers) lands in --output with the others: it was
// written past the staging folder once, which failed the run at its very end.
TEST(ComicTrackEval, WritesTheEqualCountPrecisionTableIntoTheOutputFolder) {
  ScopedTempDir dir;
  const std::string example = comic::test::ExampleDir();
  const auto result =
      RunCommand(AppPath("comic_track_eval") + " " + example + "/image_l --poses " + example +
                 "/poses.txt --calib " + example +
                 "/calib.txt --resize-height 185 --last 6 --detectors harris --baseline-matchers "
                 "full,calibrated --count 150 --overlay-frames 0 --quiet --output " +
                 dir.File("k"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json table =
      nlohmann::json::parse(ReadText(dir.File("k") + "/precision_equal_count.json"));
  EXPECT_FALSE(table.empty());
  EXPECT_NE(ReadText(dir.File("k") + "/report.html")
                .find("Epipolar precision at equal numbers of matches"),
            std::string::npos);
}

TEST(ComicTrackEval, ReportsEpipolarPrecisionOnTheBundledKittiClip) {
  ScopedTempDir dir;
  const std::string example = comic::test::ExampleDir();
  const auto result =
      RunCommand(AppPath("comic_track_eval") + " " + example + "/image_l --poses " + example +
                 "/poses.txt --calib " + example +
                 "/calib.txt --resize-height 185 --last 6 "
                 "--detectors harris,fast --count 150 --overlay-frames 1 --output " +
                 dir.File("k"));
  ASSERT_EQ(result.exit_code, 0) << result.output;
  const nlohmann::json precision =
      nlohmann::json::parse(ReadText(dir.File("k") + "/precision_n5.json"));
  ASSERT_EQ(precision.size(), 2u);
  for (const auto& row : precision) {
    EXPECT_GT(row["matches/pair @T"].get<double>(), 10.0) << row.dump();
    EXPECT_GT(row["precision @T %"].get<double>(), 50.0) << row.dump();
    EXPECT_LE(row["precision @T %"].get<double>(), 100.0);
  }
  const std::string page = ReadText(dir.File("k") + "/report.html");
  EXPECT_NE(page.find("Epipolar precision, n = 5"), std::string::npos);
  // Only full-patch matchers: no equal-count table (as no precision_equal_count.*).
  EXPECT_EQ(page.find("Epipolar precision at equal numbers of matches"), std::string::npos);
  // Without a region, only "overall" is defined.
  const nlohmann::json scores = nlohmann::json::parse(ReadText(dir.File("k") + "/scores_n5.json"));
  EXPECT_TRUE(scores[0]["M_score(5) % boundary"].is_null());
  EXPECT_TRUE(scores[0]["M_score(5) % overall"].is_number());
}

TEST(ComicTrackEval, IsDeterministic) {
  ScopedTempDir dir;
  WriteSyntheticSequence(dir.path());
  const std::string base = AppPath("comic_track_eval") + " " + dir.File("frames") + " --masks " +
                           dir.File("masks") + kFastArgs + " --overlay-frames 0 --output ";
  ASSERT_EQ(RunCommand(base + dir.File("a")).exit_code, 0);
  ASSERT_EQ(RunCommand(base + dir.File("b") + " --threads 2").exit_code, 0);
  nlohmann::json a = nlohmann::json::parse(ReadText(dir.File("a") + "/evaluation.json"));
  nlohmann::json b = nlohmann::json::parse(ReadText(dir.File("b") + "/evaluation.json"));
  a.erase("command");
  b.erase("command");
  EXPECT_TRUE(a == b) << "evaluation.json differs between runs";
  EXPECT_EQ(ReadText(dir.File("a") + "/scores_n5.csv"), ReadText(dir.File("b") + "/scores_n5.csv"));
}

TEST(ComicTrackEval, BadInputGivesOneLineErrorAndNonZeroExit) {
  ScopedTempDir dir;
  WriteSyntheticSequence(dir.path());
  std::filesystem::create_directories(dir.File("empty"));
  std::filesystem::create_directories(dir.File("few_masks"));
  std::filesystem::copy(dir.File("masks/000.png"), dir.File("few_masks/000.png"));
  std::filesystem::create_directories(dir.File("big_masks"));
  for (int i = 0; i < 8; ++i) {
    char name[32];
    std::snprintf(name, sizeof(name), "/%03d.png", i);
    cv::imwrite(dir.File("big_masks") + name, cv::Mat(151, 200, CV_8UC1, cv::Scalar(255)));
  }
  {
    std::ofstream short_boxes(dir.File("short.txt"));
    short_boxes << "10 10 20 20\n10 10 20 20\n";
  }
  const std::string frames = dir.File("frames");
  const std::string ok = " --detectors harris --count 10 --output " + dir.File("o");
  struct Case {
    std::string args;
    int exit_code;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"", 2, "missing argument FRAMES"},
      {dir.File("empty") + ok, 2, "folder holds no images"},
      {dir.File("missing") + ok, 1, "no such file or folder"},
      {frames + " --masks " + dir.File("few_masks") + ok, 1, "1 masks for 8 frames"},
      {frames + " --masks " + dir.File("big_masks") + ok, 1,
       "mask is 200x151 but the frames are 200x150"},
      {frames + " --detectors harris,sift --count 10", 2, "unknown detector 'sift'"},
      {frames + ok + " --n 8", 2, "--n 8 needs at least 9 frames"},
      {frames + ok + " --n 0", 2, "--n must be >= 1"},
      {frames + " --masks " + dir.File("masks") + " --regions " + dir.File("boxes.txt") + ok, 2,
       "either --masks or --regions"},
      {frames + " --regions " + dir.File("short.txt") + ok, 1,
       "2 regions, but frame 7 needs line 8"},
      {frames + " --poses " + comic::test::ExampleDir() + "/poses.txt" + ok, 2,
       "--poses and --calib go together"},
      {frames + " --detectors harris", 2, "give the feature count N"},
      {frames + ok + " --comic-matchers ncc", 2, "unknown match cost 'ncc'"},
      {frames + ok + " --search-radius 0", 2, "--search-radius must be > 0"},
      {frames + ok + " --sweep 100,x", 2, "--sweep: expected a number or inf, got 'x'"},
      {frames + ok + " --bogus", 2, "unknown option --bogus"},
      {frames + " --detectors harris --count 10 --output /proc/none", 1, "cannot create"},
  };
  for (const Case& c : cases) {
    const auto result = RunCommand(AppPath("comic_track_eval") + " " + c.args);
    EXPECT_EQ(result.exit_code, c.exit_code) << c.args << "\n" << result.output;
    EXPECT_NE(result.output.find(c.message), std::string::npos) << c.args << "\n" << result.output;
    EXPECT_EQ(comic::test::CountLines(result.output), 1) << c.args << "\n" << result.output;
  }
  EXPECT_FALSE(std::filesystem::exists(dir.File("o") + "/scores_n5.md"));
}

}  // namespace
