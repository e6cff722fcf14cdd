// The per-frame diagnostics and the residual histogram of report.html on a synthetic run with
// known answers: a frame whose three observations are 1.1, 2.1 and 3.1 px off has a mean error of
// 2.1 px and puts them in the 5th, 9th and 13th bins of 0.25 px; interpolated and unposed frames
// have no observations; the inliers are the mapper's.
#include "sfm/run/run_page_diagnostics.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>

namespace comic::sfm {
namespace {

// Four frames: 0 and 1 registered in one model (1 by rotation only), 2 interpolated, 3 posed by
// nothing. Three points seen by frames 0 and 1: exactly in frame 1, 1.1 + k px to the right of
// their projection in frame 0.
DetectorRun FourFrameRun() {
  DetectorRun run;
  IncrementalReconstruction& mapping = run.run.mapping;
  Reconstruction& model = mapping.reconstruction;
  const Camera camera = Camera::FromImageSize(64, 48);
  const camera_t camera_id = model.AddCamera(camera);
  std::vector<Eigen::Vector3d> points;
  for (int k = 0; k < 3; ++k) points.emplace_back(0.1 * k, 0.05 * k, 5.0);
  for (int f = 0; f < 4; ++f) {
    Image image;
    image.camera_id = camera_id;
    image.name = "frame" + std::to_string(f);
    image.cam_from_world.translation = Eigen::Vector3d(-0.1 * f, 0, 0);
    image.points2D.resize(points.size());
    for (size_t k = 0; k < points.size(); ++k) {
      image.points2D[k].xy = *ProjectPoint(camera, image.cam_from_world, points[k]);
      if (f == 0) image.points2D[k].xy.x() += 1.1 + static_cast<double>(k);
    }
    model.AddImage(image);
  }
  model.RegisterImage(1);
  model.RegisterImage(2);
  for (size_t k = 0; k < points.size(); ++k) {
    const point2D_t index = static_cast<point2D_t>(k);
    model.AddPoint3D(points[k], {{1, index}, {2, index}});
  }
  mapping.status = ReconstructionStatus::kPartial;
  mapping.registered_frames = {0, 1};
  mapping.rotation_only_frames = {1};
  mapping.unregistered_frames = {2, 3};
  mapping.interpolated_frames = {2};
  mapping.interpolated_poses = {Rigid3d()};
  run.pose_inliers = {-1, 57, -1, -1};
  return run;
}

TEST(RunFrameDiagnostics, MeasuresEachFrameInItsModel) {
  const std::vector<FrameDiagnostics> frames = RunFrameDiagnostics(FourFrameRun(), 4);
  ASSERT_EQ(frames.size(), 4u);
  EXPECT_EQ(frames[0].model, 0);
  EXPECT_EQ(PoseWords(frames[0]), "registered");
  EXPECT_EQ(frames[0].observations, 3);
  EXPECT_EQ(frames[0].pnp_inliers, -1);  // the initial pair: no PnP
  EXPECT_NEAR(frames[0].mean_error_px, (1.1 + 2.1 + 3.1) / 3, 1e-9);
  EXPECT_EQ(PoseWords(frames[1]), "rotation only");
  EXPECT_EQ(frames[1].observations, 3);
  EXPECT_EQ(frames[1].pnp_inliers, 57);
  EXPECT_NEAR(frames[1].mean_error_px, 0.0, 1e-9);
  EXPECT_EQ(frames[2].model, 0);
  EXPECT_EQ(PoseWords(frames[2]), "interpolated");
  EXPECT_EQ(frames[2].observations, 0);
  EXPECT_TRUE(std::isnan(frames[2].mean_error_px));
  EXPECT_EQ(frames[3].model, -1);
  EXPECT_EQ(PoseWords(frames[3]), "none");
}

TEST(RunReprojectionErrors, HistogramOfAKnownRun) {
  const std::vector<double> errors = RunReprojectionErrors(FourFrameRun());
  ASSERT_EQ(errors.size(), 6u);
  // 0, 0, 0, 1.1, 2.1, 3.1 px: the 99th percentile 3.1 rounds up to 5 px, 20 bins of 0.25 px.
  const ErrorHistogram histogram = HistogramOfErrors(errors, 20);
  EXPECT_DOUBLE_EQ(histogram.bin_width_px, 0.25);
  std::vector<int64_t> expected(20, 0);
  expected[0] = 3;
  expected[4] = expected[8] = expected[12] = 1;
  EXPECT_EQ(histogram.counts, expected);
  EXPECT_EQ(histogram.overflow, 0);
  EXPECT_EQ(histogram.total, 6);
}

TEST(HistogramOfErrors, KeepsAFewWildErrorsOutOfTheScale) {
  // 0.5, 1 and 1.5 px: up to 2 px in bins of 0.1.
  const ErrorHistogram round = HistogramOfErrors({1.5, 0.5, 1.0}, 20);
  EXPECT_DOUBLE_EQ(round.bin_width_px, 0.1);
  EXPECT_EQ(round.counts[5] + round.counts[10] + round.counts[15], 3);
  // 200 errors of 0.31 px, one of 50 px, one behind its camera: up to 0.5 px, two beyond.
  std::vector<double> wild(200, 0.31);
  wild.push_back(50.0);
  wild.push_back(std::numeric_limits<double>::infinity());
  const ErrorHistogram histogram = HistogramOfErrors(wild, 20);
  EXPECT_DOUBLE_EQ(histogram.bin_width_px, 0.025);
  EXPECT_EQ(histogram.counts[12], 200);
  EXPECT_EQ(histogram.overflow, 2);
  EXPECT_EQ(histogram.total, 202);
  // None: one empty scale of 1 px.
  const ErrorHistogram none = HistogramOfErrors({}, 20);
  EXPECT_DOUBLE_EQ(none.bin_width_px, 0.05);
  EXPECT_EQ(none.total, 0);
}

TEST(FrameDiagnosticsSections, ATableRowPerFrameChartsAndTheHistogram) {
  const std::vector<io::PageSection> sections =
      FrameDiagnosticsSections(FourFrameRun(), {"a.png", "b.png", "c.png", "d.png"});
  ASSERT_EQ(sections.size(), 4u);
  EXPECT_EQ(sections[0]["type"], "lines");
  EXPECT_EQ(sections[0]["series"][0]["y"], nlohmann::json({3.0, 3.0, nullptr, nullptr}));
  EXPECT_EQ(sections[0]["series"][1]["y"], nlohmann::json({nullptr, 57.0, nullptr, nullptr}));
  EXPECT_EQ(sections[0]["marks"][0]["x"], nlohmann::json({3.0}));  // no pose
  EXPECT_EQ(sections[0]["marks"][1]["x"], nlohmann::json({2.0}));  // interpolated
  EXPECT_EQ(sections[1]["y_label"], "mean reprojection error (px)");
  const io::PageSection& table = sections[2];
  EXPECT_EQ(table["type"], "table");
  EXPECT_TRUE(table["scroll"].get<bool>());
  ASSERT_EQ(table["rows"].size(), 4u);
  EXPECT_EQ(table["rows"][0],
            nlohmann::json({"0", "a.png", "sparse/0", "registered", "3", "", "2.100"}));
  EXPECT_EQ(table["rows"][1],
            nlohmann::json({"1", "b.png", "sparse/0", "rotation only", "3", "57", "0.000"}));
  EXPECT_EQ(table["rows"][2],
            nlohmann::json({"2", "c.png", "sparse/0", "interpolated", "", "", ""}));
  EXPECT_EQ(table["rows"][3], nlohmann::json({"3", "d.png", "", "none", "", "", ""}));
  const io::PageSection& histogram = sections[3];
  EXPECT_EQ(histogram["type"], "histogram");
  EXPECT_EQ(histogram["counts"][4], 1);
  EXPECT_DOUBLE_EQ(histogram["edges"].back().get<double>(), 5.0);
  EXPECT_EQ(histogram["note"].get<std::string>().rfind("6 observations of the 1 model", 0), 0u);
  // A failed run: no model, no diagnostics.
  DetectorRun failed;
  EXPECT_TRUE(FrameDiagnosticsSections(failed, {"a.png"}).empty());
}

}  // namespace
}  // namespace comic::sfm
