// DiagnoseReconstruction on synthetic scenes whose failure is known: a panning camera (a
// homography explains every pair), thresholds set out of reach (shared tracks, parallax score,
// initial points), too few frames, and a success.
#include "sfm/reconstruction_diagnosis.h"

#include <gtest/gtest.h>

#include "sfm/synthetic_scene.h"

namespace comic::sfm {
namespace {

struct DiagnosedRun {
  SyntheticScene scene;
  IncrementalReconstruction result;
  ReconstructionDiagnosis diagnosis;
};

DiagnosedRun Reconstruct(const SyntheticSceneOptions& scene_options,
                         const IncrementalPipelineOptions& options) {
  DiagnosedRun run;
  run.scene = MakeSyntheticScene(scene_options);
  run.result = ReconstructIncrementally(run.scene.tracks, run.scene.camera, options);
  run.diagnosis = DiagnoseReconstruction(run.result, options, run.scene.tracks.frame_names);
  return run;
}

bool Contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(ReconstructionDiagnosis, APanningCameraIsReportedAsRotationOnly) {
  SyntheticSceneOptions scene_options;
  scene_options.motion = SyntheticMotion::kPureRotation;
  scene_options.num_frames = 12;
  const DiagnosedRun run = Reconstruct(scene_options, IncrementalPipelineOptions());
  ASSERT_EQ(run.result.status, ReconstructionStatus::kNoInitialPair);
  const ReconstructionDiagnosis& d = run.diagnosis;
  EXPECT_TRUE(d.failed);
  EXPECT_EQ(d.stage, "initial_pair");
  EXPECT_EQ(d.check, "two_view_geometry");
  EXPECT_TRUE(d.rotation_only);
  // No parallax at all: a homography explains (nearly) every inlier, more than the 80 % allowed.
  EXPECT_GT(d.value, 0.8);
  EXPECT_DOUBLE_EQ(d.needed, 0.8);
  EXPECT_NE(d.frame1, d.frame2);
  EXPECT_TRUE(Contains(d.message, d.frame1 + "-" + d.frame2)) << d.message;
  EXPECT_TRUE(Contains(d.message, "homography")) << d.message;
  EXPECT_TRUE(Contains(d.message, "panning")) << d.message;
  EXPECT_EQ(d.message.find('\n'), std::string::npos);
  // 12 frames, all within the default gap of 20: a larger gap cannot help, only other footage.
  EXPECT_FALSE(Contains(d.suggestion, "--init-max-gap")) << d.suggestion;
  EXPECT_TRUE(Contains(d.suggestion, "moves sideways")) << d.suggestion;
  EXPECT_GT(run.result.initial_pair_search.num_pairs_verified, 0);
  EXPECT_EQ(run.result.initial_pair_search.num_pairs_qualified, 0);
}

TEST(ReconstructionDiagnosis, AParallaxScoreOutOfReachSaysHowCloseTheBestPairCame) {
  SyntheticSceneOptions scene_options;
  scene_options.num_frames = 12;
  scene_options.num_points = 400;
  IncrementalPipelineOptions options;
  options.mapper.init_min_score = 1e6;
  options.mapper.init_max_frame_gap = 4;
  const DiagnosedRun run = Reconstruct(scene_options, options);
  ASSERT_EQ(run.result.status, ReconstructionStatus::kNoInitialPair);
  const ReconstructionDiagnosis& d = run.diagnosis;
  EXPECT_EQ(d.check, "parallax");
  EXPECT_FALSE(d.rotation_only);
  EXPECT_DOUBLE_EQ(d.needed, 1e6);
  // The score is at most one per inlier and the inliers are at most the shared tracks.
  const IncrementalMapper::InitialPairSearch& search = run.result.initial_pair_search;
  EXPECT_GT(d.value, 30.0);
  EXPECT_LE(d.value, search.num_inliers);
  EXPECT_LE(search.num_inliers, search.num_shared_tracks);
  EXPECT_LE(search.num_shared_tracks, 400);
  EXPECT_TRUE(Contains(d.message, "parallax score")) << d.message;
  EXPECT_TRUE(Contains(d.message, "needs 1000000.0")) << d.message;
  EXPECT_TRUE(Contains(d.suggestion, "--init-max-gap 8")) << d.suggestion;

  // Twice the best score needed: half the --init-angle would double an unsaturated score.
  options.mapper.init_min_score = 2.0 * d.value * (1.0 - 1e-9);
  const DiagnosedRun twice = Reconstruct(scene_options, options);
  ASSERT_EQ(twice.result.status, ReconstructionStatus::kNoInitialPair);
  EXPECT_DOUBLE_EQ(twice.diagnosis.value, d.value);  // the same search, the same best pair
  EXPECT_TRUE(Contains(twice.diagnosis.suggestion, "--init-angle 2.0"))
      << twice.diagnosis.suggestion;
}

TEST(ReconstructionDiagnosis, TooFewSharedTracksNamesTheCountAndTheThreshold) {
  SyntheticSceneOptions scene_options;
  scene_options.num_frames = 6;
  scene_options.num_points = 200;
  IncrementalPipelineOptions options;
  options.mapper.init_min_num_matches = 100000;
  const DiagnosedRun run = Reconstruct(scene_options, options);
  ASSERT_EQ(run.result.status, ReconstructionStatus::kNoInitialPair);
  EXPECT_EQ(run.diagnosis.check, "shared_tracks");
  EXPECT_GT(run.diagnosis.value, 50.0);
  EXPECT_LE(run.diagnosis.value, 200.0);
  EXPECT_TRUE(Contains(run.diagnosis.message, "needs 100000")) << run.diagnosis.message;
  EXPECT_TRUE(Contains(run.diagnosis.suggestion, "--max-features")) << run.diagnosis.suggestion;
  // Nothing was verified: the search stopped at the shared-track count.
  EXPECT_EQ(run.result.initial_pair_search.num_pairs_verified, 0);
}

TEST(ReconstructionDiagnosis, TooFewInitialPointsNamesThePairAndItsPoints) {
  SyntheticSceneOptions scene_options;
  scene_options.num_frames = 6;
  scene_options.num_points = 200;
  IncrementalPipelineOptions options;
  options.min_num_initial_points = 100000;
  options.max_num_models = 1;
  const DiagnosedRun run = Reconstruct(scene_options, options);
  ASSERT_EQ(run.result.status, ReconstructionStatus::kTooFewPoints);
  EXPECT_EQ(run.diagnosis.stage, "initial_points");
  EXPECT_GT(run.diagnosis.value, 30.0);  // it triangulated points, just not 100000
  EXPECT_LE(run.diagnosis.value, 200.0);
  EXPECT_DOUBLE_EQ(run.diagnosis.needed, 100000.0);
  EXPECT_FALSE(run.diagnosis.frame1.empty());
  EXPECT_TRUE(Contains(run.diagnosis.message, "needs 100000")) << run.diagnosis.message;
}

TEST(ReconstructionDiagnosis, TooFewFramesAndSuccess) {
  SyntheticSceneOptions scene_options;
  scene_options.num_frames = 1;
  const DiagnosedRun single = Reconstruct(scene_options, IncrementalPipelineOptions());
  EXPECT_EQ(single.diagnosis.check, "frames");
  EXPECT_TRUE(Contains(single.diagnosis.message, "too few frames"));
  scene_options.num_frames = 5;
  scene_options.num_points = 300;
  const DiagnosedRun success = Reconstruct(scene_options, IncrementalPipelineOptions());
  ASSERT_EQ(success.result.status, ReconstructionStatus::kSuccess);
  EXPECT_FALSE(success.diagnosis.failed);
  EXPECT_TRUE(success.diagnosis.message.empty());
  // The search is reported on success too: the pair it started from qualified.
  EXPECT_EQ(success.result.initial_pair_search.stage,
            IncrementalMapper::InitialPairSearch::Stage::kQualified);
}

}  // namespace
}  // namespace comic::sfm
