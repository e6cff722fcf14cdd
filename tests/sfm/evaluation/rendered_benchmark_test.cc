// The boundary benchmark on a rendered sequence (sfm/evaluation/rendered_benchmark.h): the test
// street rendered here (render/ is linked for that only), then one detector's run judged against
// the truth read back from the files.
#include "sfm/evaluation/rendered_benchmark.h"

#include <gtest/gtest.h>

#include <cmath>
#include <iostream>
#include <nlohmann/json.hpp>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/image/image_io.h"
#include "render/scene_builder.h"
#include "render/sequence_renderer.h"
#include "tests/test_support.h"

namespace comic::sfm {
namespace {

TEST(RenderedBenchmark, OneDetectorOnTheTestStreet) {
  test::ScopedTempDir dir;
  render::SceneBuildOptions build;
  build.num_frames = 10;
  const render::BuiltScene built =
      render::BuildScene(test::SourceDir() + "/scenes/test_street.json",
                         {test::ExampleDir() + "/image_l/000000.png"}, 3, build);
  render::RenderSequence(built, 3, render::SequenceRenderOptions(), dir.path());

  RenderedBenchmarkOptions options;
  options.detectors = {"harris"};
  options.reconstruction.mapper.mapper.ignore_two_view_tracks = true;
  const RenderedBenchmark result = RunRenderedBenchmark(dir.path(), options);
  ASSERT_EQ(result.detectors.size(), 1u);
  const DetectorBenchmark& d = result.detectors[0];
  EXPECT_EQ(result.num_frames, 10);
  EXPECT_GT(d.num_features, 5000u);
  // Some features lie in the band, and the band is a small part of the image.
  EXPECT_GT(d.num_boundary_features, 0u);
  EXPECT_GT(d.boundary_area_fraction, 0.01);
  EXPECT_LT(d.boundary_area_fraction, 0.3);
  EXPECT_GT(d.boundary_tracks.num_tracks, 0u);
  // Away from boundaries most tracks follow a surface point to an RMS of 1.5 px (on
  // this drive ~60 %: forward motion zooms the textures, and a corner detected at a fixed scale
  // creeps over a zoomed texture; docs/rendered_benchmark.md).
  EXPECT_GT(d.other_tracks.num_classified, 500u);
  EXPECT_GT(d.other_tracks.FollowingFraction(), 0.5);
  EXPECT_LT(d.other_tracks.median_drift_px, 2.0);
  EXPECT_EQ(d.model.status, "success");
  EXPECT_EQ(d.model.num_registered, 10);
  ASSERT_TRUE(d.model.ate_rmse.has_value());
  EXPECT_LT(*d.model.ate_rmse, 0.05);
  EXPECT_GT(d.points.num_points, 300u);
  EXPECT_GE(d.boundary_error_share, 0.0);
  EXPECT_LE(d.boundary_error_share, 1.0);
  ASSERT_TRUE(d.without_boundary.has_value());
  EXPECT_LT(d.without_boundary->num_tracks, d.model.num_tracks);
  ASSERT_TRUE(d.without_sliding.has_value());
  EXPECT_EQ(d.without_sliding->status, "success");
  // The labeller, without truth, calls some tracks sliding, and most of those slide in truth.
  const LabelAgreement& labels = d.labelled_sliding;
  std::cout << "labelled sliding " << labels.num_labelled_sliding << ", sliding in truth "
            << labels.num_true_sliding << ", both " << labels.num_both << std::endl;
  EXPECT_GT(labels.num_labelled_sliding, 50u);
  EXPECT_GT(labels.Precision(), 0.7);
  EXPECT_GT(labels.Recall(), 0.5);
  ASSERT_EQ(d.track_scores.size(), d.model.num_tracks);
  ASSERT_TRUE(d.without_labelled_sliding.has_value());
  EXPECT_EQ(d.without_labelled_sliding->status, "success");
  EXPECT_LT(d.without_labelled_sliding->num_tracks, d.model.num_tracks);
  // The table and JSON hold the row; the per-track table a row per track.
  EXPECT_EQ(result.Table().NumRows(), 1u);
  EXPECT_EQ(result.ToJson()["runs"][0]["detector"], "harris");
  EXPECT_EQ(result.TrackScoreTable(0).NumRows(), d.track_scores.size());
}

// The test street with `extra` elements, `frames` frames.
render::BuiltScene TestStreet(const std::vector<nlohmann::json>& extra, int frames) {
  nlohmann::json spec =
      nlohmann::json::parse(io::ReadFileToString(test::SourceDir() + "/scenes/test_street.json"));
  for (const nlohmann::json& element : extra) spec["elements"].push_back(element);
  const std::string photo = test::ExampleDir() + "/image_l/000000.png";
  render::SceneBuildOptions build;
  build.num_frames = frames;
  return render::BuildSceneFromJson(spec, "test_street.json", test::SourceDir() + "/scenes",
                                    {io::LoadImage(photo).color}, {photo}, 3, build);
}

// Harris's ordinary run (no masks) on `built` rendered through `sensor`.
ModelSummary MapRendered(const render::BuiltScene& built, const render::SensorOptions& sensor) {
  test::ScopedTempDir dir;
  render::SequenceRenderOptions render_options;
  render_options.sensor = sensor;
  render::RenderSequence(built, 3, render_options, dir.path());
  RenderedBenchmarkOptions options;
  options.detectors = {"harris"};
  options.without_boundary_tracks = false;
  options.without_sliding_tracks = false;
  const RenderedBenchmark result = RunRenderedBenchmark(dir.path(), options);
  EXPECT_EQ(result.num_frames, built.num_frames);
  const ModelSummary& model = result.detectors.at(0).model;
  std::cout << model.status << ": " << model.num_registered << "/" << built.num_frames
            << " frames registered, ATE " << (model.ate_rmse ? *model.ate_rmse : -1.0) << " m, "
            << model.num_points << " points" << std::endl;
  return model;
}

TEST(RenderedBenchmark, HeavyMotionBlurOnEveryOtherFrameStillRegistersEveryFrame) {
  // The shutter open the whole interval: every odd frame smeared over the 0.8 m the camera drives
  // between frames, the even frames sharp.
  render::SensorOptions sensor;
  sensor.shutter = 1.0;
  sensor.blur_samples = 8;
  sensor.blur_every = 2;
  const ModelSummary model = MapRendered(TestStreet({}, 12), sensor);
  EXPECT_EQ(model.status, "success");
  EXPECT_EQ(model.num_registered, 12);
  ASSERT_TRUE(model.ate_rmse.has_value());
  EXPECT_LT(*model.ate_rmse, 0.05);
}

// Disabled: the pipeline does not yet pass it (docs/results.md, issue 47: the truck is the larger
// rigid body in every frame, and the model is built on it; two-view geometry of consecutive
// frames does not tell its motion from the street's).
TEST(RenderedBenchmark, DISABLED_AnObjectMovingThroughTheViewKeepsTheTrajectoryError) {
  // A truck-sized box (4 m wide, 3 m high) 8 m ahead and 3.5 m to the right of the first camera,
  // moving away at 0.5 m per frame while it crosses to the left at 0.5 m per frame: nearer at each
  // frame (the camera drives 0.8 m per frame), a large part of every view. No masks: the run has
  // to tell its features from the street's.
  constexpr int kFrames = 12;
  const render::BuiltScene street = TestStreet({}, kFrames);
  const render::Pose start = street.path.At(0);
  const Eigen::Vector3d forward = start.rotation.transpose() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d right = start.rotation.transpose() * Eigen::Vector3d::UnitX();
  const Eigen::Vector3d center = start.Center() + 8.0 * forward + 3.5 * right;
  const Eigen::Vector3d velocity = 0.5 * forward - 0.5 * right;
  const nlohmann::json truck = {{"type", "box"},
                                {"center", {center.x(), center.z()}},
                                {"size", {4.0, 3.0, 2.0}},
                                {"yaw_deg", std::atan2(right.z(), right.x()) * 180.0 / M_PI},
                                {"velocity", {velocity.x(), 0.0, velocity.z()}}};
  const render::BuiltScene with_truck = TestStreet({truck}, kFrames);
  ASSERT_TRUE(with_truck.scene.HasMotion());

  const ModelSummary without = MapRendered(street, render::SensorOptions());
  const ModelSummary with = MapRendered(with_truck, render::SensorOptions());
  ASSERT_EQ(without.status, "success");
  ASSERT_TRUE(without.ate_rmse.has_value());
  EXPECT_EQ(with.status, "success");
  EXPECT_EQ(with.num_registered, kFrames);
  ASSERT_TRUE(with.ate_rmse.has_value());
  // Within half as much again as without it, plus 5 mm.
  EXPECT_LT(*with.ate_rmse, 1.5 * *without.ate_rmse + 0.005);
}

TEST(RenderedBenchmark, AFolderWithoutTruthOrABadDetectorIsAnError) {
  test::ScopedTempDir dir;
  EXPECT_THROW(RunRenderedBenchmark(dir.path(), RenderedBenchmarkOptions()), Error);
  RenderedBenchmarkOptions options;
  options.detectors = {"sift"};
  EXPECT_THROW(RunRenderedBenchmark(dir.path(), options), Error);
}

}  // namespace
}  // namespace comic::sfm
