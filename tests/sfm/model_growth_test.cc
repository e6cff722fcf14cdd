// Growing one model: a self-calibrated camera that leaves the plausible range is reset to its
// prior and held, and an earlier model the growth reaches is merged instead of grown again.
#include "sfm/model_growth.h"

#include <gtest/gtest.h>

#include "sfm/synthetic_scene.h"

namespace comic::sfm {
namespace {

SyntheticScene HandHeldScene() {
  SyntheticSceneOptions options;
  options.motion = SyntheticMotion::kHandHeld;
  options.num_frames = 14;
  options.num_points = 800;
  options.noise_px = 0.3;
  options.outlier_ratio = 0.05;
  options.model = CameraModelId::kSimpleRadial;
  return MakeSyntheticScene(options);
}

TEST(ModelGrowth, AnImplausibleSelfCalibrationIsResetToThePrior) {
  const SyntheticScene scene = HandHeldScene();
  Camera prior = scene.camera;  // f = 600
  prior.fx = prior.fy = 660.0;
  IncrementalPipelineOptions options;
  options.global_ba.refine_focal_length = true;
  options.global_ba.refine_extra_params = true;
  const auto pair = IncrementalMapper(scene.tracks, prior, options.mapper).FindInitialPair();
  ASSERT_TRUE(pair.has_value());
  // Within the plausible range the refined focal is kept.
  const GrownModel refined = GrowModel(scene.tracks, prior, options, *pair, 0, {}, {}, {});
  ASSERT_EQ(refined.status, ReconstructionStatus::kSuccess);
  EXPECT_TRUE(refined.intrinsics_refined);
  EXPECT_FALSE(refined.intrinsics_rejection.rejected);
  EXPECT_NEAR(refined.model.reconstruction.cameras().begin()->second.fx, 600.0, 3.0);
  // A range that 600 / 660 leaves: the camera goes back to the prior, held, and says why.
  options.plausible_intrinsics.max_focal_ratio = 1.05;
  const GrownModel held = GrowModel(scene.tracks, prior, options, *pair, 0, {}, {}, {});
  ASSERT_EQ(held.status, ReconstructionStatus::kSuccess);
  EXPECT_FALSE(held.intrinsics_refined);
  ASSERT_TRUE(held.intrinsics_rejection.rejected);
  EXPECT_NEAR(held.intrinsics_rejection.rejected_camera.fx, 600.0, 10.0);
  EXPECT_NE(held.intrinsics_rejection.reason.find("focal length"), std::string::npos);
  const Camera& camera = held.model.reconstruction.cameras().begin()->second;
  EXPECT_EQ(camera.fx, 660.0);
  EXPECT_EQ(camera.k1, 0.0);
  EXPECT_EQ(held.model.registered_frames.size(), scene.cams_from_world.size());
}

TEST(ModelGrowth, MergesAnEarlierModelOnceItOverlapsIt) {
  const SyntheticScene scene = HandHeldScene();
  IncrementalPipelineOptions options;
  options.merge_overlap_frames = 3;
  IncrementalMapper searcher(scene.tracks, scene.camera, options.mapper);
  const auto first_pair = searcher.FindInitialPair();
  ASSERT_TRUE(first_pair.has_value());
  const GrownModel first =
      GrowModel(scene.tracks, scene.camera, options, *first_pair, 0, {}, {}, {});
  ASSERT_EQ(first.model.registered_frames.size(), scene.cams_from_world.size());
  // Another start, elsewhere: its growth reaches the first model's frames and merges it after
  // merge_overlap_frames of them.
  const auto second_pair = searcher.FindInitialPair({first_pair->image_id1, first_pair->image_id2});
  ASSERT_TRUE(second_pair.has_value());
  int num_merged_reports = 0;
  const GrownModel second =
      GrowModel(scene.tracks, scene.camera, options, *second_pair, 1, {&first.model}, {},
                [&](const MapperProgress& progress) { num_merged_reports += progress.merged; });
  EXPECT_EQ(second.merged, std::vector<size_t>{0});
  EXPECT_EQ(second.model.num_merged_models, 1);
  EXPECT_EQ(second.model.registered_frames.size(), scene.cams_from_world.size());
  EXPECT_GT(num_merged_reports, 0);
  // It registered by itself only what it needed to overlap the first model.
  EXPECT_LT(second.ba.num_local_ba, first.ba.num_local_ba);
}

TEST(ModelGrowth, ABoundedFinalAdjustmentSweepsTheModelOnce) {
  const SyntheticScene scene = HandHeldScene();
  IncrementalPipelineOptions options;
  const auto pair = IncrementalMapper(scene.tracks, scene.camera, options.mapper).FindInitialPair();
  ASSERT_TRUE(pair.has_value());
  // One final adjustment of everything, then another after the tracks are completed.
  const GrownModel whole = GrowModel(scene.tracks, scene.camera, options, *pair, 0, {}, {}, {});
  ASSERT_EQ(whole.status, ReconstructionStatus::kSuccess);
  EXPECT_EQ(whole.ba.num_final_ba_windows, 0);
  EXPECT_EQ(whole.final_ba.num_variable_images, 13);  // one pose fixes the gauge
  // Windows of 4 frames, half overlapping, over the 14 frames: one sweep of 6 windows. (Here
  // completing the tracks recovers nothing after it either way; on the rendered loop drive it
  // recovered 2576 points, and the second sweep they called for is what a bounded final
  // adjustment now leaves out, docs/long_video.md.)
  options.global_ba_max_images = 4;
  const GrownModel bounded = GrowModel(scene.tracks, scene.camera, options, *pair, 0, {}, {}, {});
  ASSERT_EQ(bounded.status, ReconstructionStatus::kSuccess);
  EXPECT_EQ(bounded.model.registered_frames.size(), scene.cams_from_world.size());
  EXPECT_EQ(bounded.ba.num_final_ba_windows, 6);
  EXPECT_LE(bounded.final_ba.num_variable_images, 4);
}

}  // namespace
}  // namespace comic::sfm
