// The run report: every number of a run in JSON, and the comparison table with empty cells where
// a run has no number.
#include "sfm/evaluation/sfm_report.h"

#include <gtest/gtest.h>

namespace comic::sfm {
namespace {

SfmRunReport MakeReport(const std::string& detector, bool with_truth) {
  SfmRunReport report;
  report.detector = detector;
  report.status = "success";
  report.num_frames = 12;
  report.stats.num_images = 12;
  report.stats.num_registered = 11;
  report.stats.all = {500, 1500, 3.0, 0.45};
  report.wall_time_s = 2.5;
  if (with_truth) {
    TrajectoryEvaluation evaluation;
    evaluation.frames = {0, 1, 2};
    evaluation.ate_rmse = 0.05;
    evaluation.path_length = 10.0;
    evaluation.ate_fraction_of_path = 0.005;
    evaluation.end_to_start_error = 0.25;
    evaluation.mean_rotation_error_deg = 0.25;
    report.trajectory = evaluation;
  }
  return report;
}

TEST(SfmReport, JsonHoldsTheNumbers) {
  const nlohmann::json json = RunReportToJson(MakeReport("harris", true));
  EXPECT_EQ(json["detector"], "harris");
  EXPECT_EQ(json["registered_frames"], 11);
  EXPECT_EQ(json["points3D"]["points"], 500);
  EXPECT_DOUBLE_EQ(json["points3D"]["mean_reprojection_error_px"].get<double>(), 0.45);
  EXPECT_DOUBLE_EQ(json["ground_truth"]["ate_rmse"].get<double>(), 0.05);
  EXPECT_DOUBLE_EQ(json["ground_truth"]["ate_fraction_of_path"].get<double>(), 0.005);
  EXPECT_DOUBLE_EQ(json["ground_truth"]["end_to_start_error"].get<double>(), 0.25);
  EXPECT_DOUBLE_EQ(json["time_s"]["per_frame"].get<double>(), 2.5 / 12);
  EXPECT_TRUE(RunReportToJson(MakeReport("fast", false))["ground_truth"].is_null());
}

TEST(SfmReport, ComparisonTable) {
  SfmRunReport failed = MakeReport("mser", false);
  failed.status = "no_initial_pair";
  failed.stats = ReconstructionStats();
  const io::ReportTable table = MakeComparisonTable({MakeReport("harris", true), failed});
  ASSERT_EQ(table.NumRows(), 2u);
  const std::vector<std::string>& columns = table.columns();
  const auto column = [&](const std::string& name) {
    return static_cast<size_t>(std::find(columns.begin(), columns.end(), name) - columns.begin());
  };
  ASSERT_LT(column("ATE % of path"), columns.size());
  EXPECT_EQ(std::get<int64_t>(table.At(0, column("registered"))), 11);
  EXPECT_DOUBLE_EQ(std::get<double>(table.At(0, column("ATE % of path"))), 0.5);
  EXPECT_DOUBLE_EQ(std::get<double>(table.At(0, column("rot. error deg"))), 0.25);
  EXPECT_TRUE(std::holds_alternative<std::monostate>(table.At(1, column("ATE m"))));
  EXPECT_TRUE(std::holds_alternative<std::monostate>(table.At(1, column("reproj. error px"))));
  EXPECT_EQ(std::get<std::string>(table.At(1, column("status"))), "no_initial_pair");
  EXPECT_EQ(column("boundary points"), columns.size());  // no region statistics, no columns
  EXPECT_NE(table.ToMarkdown().find("| harris"), std::string::npos);

  SfmRunReport with_regions = MakeReport("comic", true);
  with_regions.stats.boundary = PointSetStats{40, 120, 3.0, 0.5};
  with_regions.stats.interior = PointSetStats{60, 150, 2.5, 0.4};
  const io::ReportTable regions = MakeComparisonTable({with_regions});
  const auto& region_columns = regions.columns();
  const size_t boundary = static_cast<size_t>(
      std::find(region_columns.begin(), region_columns.end(), "boundary points") -
      region_columns.begin());
  ASSERT_LT(boundary, region_columns.size());
  EXPECT_EQ(std::get<int64_t>(regions.At(0, boundary)), 40);
}

}  // namespace
}  // namespace comic::sfm
