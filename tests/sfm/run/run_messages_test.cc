// The lines comic_sfm prints while a run goes (sfm/run/run_messages.h).
#include "sfm/run/run_messages.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <string>
#include <vector>

#include "io/report/report_table.h"
#include "sfm/run/run_outputs.h"

namespace comic::sfm {
namespace {

TEST(RunMessages, FrameRegisteredLineNamesTheFrameAndTheModel) {
  MapperProgress progress;
  progress.frame_name = "000004.png";
  progress.num_registered = 5;
  progress.num_frames = 12;
  progress.num_points3D = 612;
  progress.num_pose_inliers = 270;
  EXPECT_EQ(FrameRegisteredLine("harris", progress),
            "[harris] registered 000004.png: 5/12 frames, 612 points, 270 PnP inliers");
  progress.attempt = 1;
  progress.merged = true;
  EXPECT_EQ(FrameRegisteredLine("comic", progress),
            "[comic] model 2: registered 000004.png: 5/12 frames, 612 points (merged from an "
            "earlier model)");
}

TEST(RunMessages, AdjustmentProgressLineSaysHowFarTheSolveIs) {
  BundleAdjustmentProgress progress;
  progress.iteration = 7;
  progress.max_num_iterations = 50;
  progress.num_variable_images = 196;
  progress.num_points = 14210;
  progress.elapsed_s = 2.26;
  EXPECT_EQ(AdjustmentProgressLine("harris", progress),
            "[harris] bundle adjustment of 196 frames, 14210 points: iteration 7 of 50, 2.3 s");
}

// A run with no model, as DetectorRun holds it before its outputs are written.
DetectorRun FailedRun(const std::string& page_path) {
  DetectorRun run;
  run.detector = "harris";
  run.report.detector = "harris";
  run.report.status = "failed";
  run.report.num_frames = 40;
  run.report.wall_time_s = 2.5;
  run.page_path = page_path;
  return run;
}

// The line a user reads after a run ends with where its page is, and says nothing of a
// page when there is none (no --output: the Python door without an output folder).
TEST(RunMessages, DetectorSummaryLineEndsWithThePagePath) {
  EXPECT_EQ(DetectorSummaryLine(FailedRun("out/x/report.html")),
            "[harris] failed: 0/40 frames registered, 0 points, mean track length 0, mean "
            "reprojection error 0 px, 2.5 s; page: out/x/report.html");
  EXPECT_EQ(DetectorSummaryLine(FailedRun("")).find("page"), std::string::npos);
}

TEST(RunMessages, DetectorPagePathIsInTheDetectorsFolder) {
  ReconstructionRunOptions options;
  EXPECT_EQ(DetectorPagePath(options, "harris"), "");
  options.output = "out/x";
  EXPECT_EQ(DetectorPagePath(options, "harris"), "out/x/report.html");
  options.compare = true;
  EXPECT_EQ(DetectorPagePath(options, "fast"), "out/x/fast/report.html");
}

// --compare prints its table last; the comparison's page follows it.
TEST(RunMessages, OutcomeLinesEndWithTheComparisonPage) {
  ReconstructionRunResult result;
  io::ReportTable table({"detector", "registered"});
  table.AddRow({std::string("harris"), int64_t{12}});
  result.comparison = table;
  const std::vector<std::string> lines = RunOutcomeLines(result, "out/x", "comic_sfm", true);
  ASSERT_EQ(lines.size(), 2u);
  EXPECT_EQ(lines[1], "comic_sfm: page: out/x/report.html (each detector's in its folder)");
  EXPECT_EQ(RunOutcomeLines(result, "", "comic_sfm", true).size(), 1u);
}

}  // namespace
}  // namespace comic::sfm
