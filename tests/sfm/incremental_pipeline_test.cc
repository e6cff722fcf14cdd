// End-to-end incremental reconstruction on synthetic scenes with known cameras: hand-held and
// forward video with pixel noise and wrong observations, and the degenerate inputs that must
// come back as a status.
#include "sfm/incremental_pipeline.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "io/core/error.h"
#include "sfm/evaluation/ground_truth.h"
#include "sfm/synthetic_scene.h"
#include "sfm/trajectory_evaluation.h"

namespace comic::sfm {
namespace {

std::optional<TrajectoryEvaluation> Evaluate(const IncrementalReconstruction& result,
                                             const SyntheticScene& scene) {
  return EvaluateTrajectory(RegisteredPosesByName(result.reconstruction, scene.tracks.frame_names),
                            {scene.cams_from_world.begin(), scene.cams_from_world.end()});
}

void ExpectAccurate(const SyntheticSceneOptions& scene_options) {
  const SyntheticScene scene = MakeSyntheticScene(scene_options);
  IncrementalPipelineOptions options;
  std::vector<int> reported;
  const IncrementalReconstruction result = ReconstructIncrementally(
      scene.tracks, scene.camera, options,
      [&](const MapperProgress& progress) { reported.push_back(progress.frame); });
  ASSERT_EQ(result.status, ReconstructionStatus::kSuccess);
  EXPECT_EQ(result.reconstruction.NumRegisteredImages(), scene.cams_from_world.size());
  EXPECT_TRUE(result.unregistered_frames.empty());
  EXPECT_EQ(reported.size(), scene.cams_from_world.size());
  EXPECT_GT(result.reconstruction.NumPoints3D(), 300u);
  EXPECT_LT(result.reconstruction.ComputeMeanReprojectionError(), 1.0);
  const auto evaluation = Evaluate(result, scene);
  ASSERT_TRUE(evaluation.has_value());
  EXPECT_LT(evaluation->ate_fraction_of_path, 0.01)
      << "ATE " << evaluation->ate_rmse << " over a path of " << evaluation->path_length;
  EXPECT_LT(evaluation->mean_rotation_error_deg, 0.5);
}

TEST(IncrementalPipeline, HandHeldVideoRegistersEveryFrameAccurately) {
  SyntheticSceneOptions scene_options;
  scene_options.motion = SyntheticMotion::kHandHeld;
  scene_options.num_frames = 20;
  scene_options.num_points = 600;
  ExpectAccurate(scene_options);
}

TEST(IncrementalPipeline, ForwardMotionRegistersEveryFrameAccurately) {
  SyntheticSceneOptions scene_options;
  scene_options.motion = SyntheticMotion::kForward;
  scene_options.num_frames = 25;
  scene_options.num_points = 800;
  ExpectAccurate(scene_options);
}

// A video whose first third is weakly textured: there, only every `keep_every`-th track is
// seen (the others start at the first rich frame). The initial pair comes from the rich part, so
// the model has to grow backwards into the weak frames from few points.
TEST(IncrementalPipeline, WeakStartStillEndsInOneModelWithEveryFrame) {
  SyntheticSceneOptions scene_options;
  scene_options.motion = SyntheticMotion::kHandHeld;
  scene_options.num_frames = 24;
  scene_options.num_points = 1200;
  SyntheticScene scene = MakeSyntheticScene(scene_options);
  const int weak_frames = scene_options.num_frames / 3;
  constexpr size_t kKeepEvery = 12;
  std::vector<size_t> observations_per_frame(scene.tracks.NumFrames(), 0);
  for (size_t t = 0; t < scene.tracks.tracks.size(); ++t) {
    auto& observations = scene.tracks.tracks[t].observations;
    if (t % kKeepEvery != 0) {
      observations.erase(std::remove_if(observations.begin(), observations.end(),
                                        [&](const frontend::TrackObservation& obs) {
                                          return obs.frame < weak_frames;
                                        }),
                         observations.end());
    }
    for (const auto& obs : observations) ++observations_per_frame[obs.frame];
  }
  scene.tracks.tracks.erase(
      std::remove_if(scene.tracks.tracks.begin(), scene.tracks.tracks.end(),
                     [](const frontend::Track& track) { return track.Length() < 2; }),
      scene.tracks.tracks.end());
  // The weak frames really are weak: an order of magnitude fewer tracked features.
  ASSERT_LT(8 * observations_per_frame[0], observations_per_frame[weak_frames + 1]);
  ASSERT_GT(observations_per_frame[weak_frames - 1], 40u);

  const IncrementalReconstruction result =
      ReconstructIncrementally(scene.tracks, scene.camera, IncrementalPipelineOptions());
  ASSERT_EQ(result.status, ReconstructionStatus::kSuccess);
  EXPECT_GE(result.initial_frame1, weak_frames) << "the initial pair should be in the rich part";
  EXPECT_TRUE(result.unregistered_frames.empty())
      << result.unregistered_frames.size() << " frames left out, the first "
      << result.unregistered_frames.front();
  const auto evaluation = Evaluate(result, scene);
  ASSERT_TRUE(evaluation.has_value());
  EXPECT_LT(evaluation->ate_fraction_of_path, 0.01);
}

// COLMAP's tri_ignore_two_view_tracks: a track seen in only two frames gives no point, except
// among the initial pair's (they start the model); with ignore_two_view_tracks off such tracks
// are triangulated wherever their two frames are registered. Either way every frame registers
// near the truth, and the adjustments report their iterations.
TEST(IncrementalPipeline, TwoViewTracksGiveNoPointsUnlessAsked) {
  SyntheticSceneOptions scene_options;
  scene_options.motion = SyntheticMotion::kHandHeld;
  scene_options.num_frames = 16;
  scene_options.num_points = 900;
  SyntheticScene scene = MakeSyntheticScene(scene_options);
  // Every third track cut to its first two observations.
  for (size_t t = 0; t < scene.tracks.tracks.size(); t += 3) {
    auto& observations = scene.tracks.tracks[t].observations;
    if (observations.size() > 2) observations.resize(2);
  }
  // Per frame, per feature: the length of its track.
  std::vector<std::vector<size_t>> track_length(scene.tracks.NumFrames());
  for (size_t frame = 0; frame < scene.tracks.NumFrames(); ++frame) {
    track_length[frame].assign(scene.tracks.features[frame].size(), 0);
  }
  for (const frontend::Track& track : scene.tracks.tracks) {
    for (const auto& obs : track.observations)
      track_length[obs.frame][obs.feature] = track.Length();
  }
  // Points of two-view tracks, and of those the ones outside the initial pair's frames.
  const auto count_two_view = [&](const IncrementalReconstruction& result, int* outside) {
    int num_two_view = 0;
    *outside = 0;
    for (const auto& [id, point] : result.reconstruction.points3D()) {
      const TrackElement& element = point.track.front();
      const int frame = static_cast<int>(element.image_id) - 1;
      if (track_length[frame][element.point2D_idx] != 2) continue;
      ++num_two_view;
      for (const TrackElement& other : point.track) {
        const int f = static_cast<int>(other.image_id) - 1;
        if (f != result.initial_frame1 && f != result.initial_frame2) {
          ++*outside;
          break;
        }
      }
    }
    return num_two_view;
  };

  IncrementalPipelineOptions options;
  ASSERT_TRUE(options.mapper.ignore_two_view_tracks);  // the default
  const IncrementalReconstruction ignored =
      ReconstructIncrementally(scene.tracks, scene.camera, options);
  options.mapper.ignore_two_view_tracks = false;
  const IncrementalReconstruction kept =
      ReconstructIncrementally(scene.tracks, scene.camera, options);
  for (const IncrementalReconstruction* result : {&ignored, &kept}) {
    ASSERT_EQ(result->status, ReconstructionStatus::kSuccess);
    EXPECT_TRUE(result->unregistered_frames.empty());
    const auto evaluation = Evaluate(*result, scene);
    ASSERT_TRUE(evaluation.has_value());
    EXPECT_LT(evaluation->ate_fraction_of_path, 0.01);
    EXPECT_GE(result->num_global_ba_iterations, result->num_global_ba);
    EXPECT_GE(result->num_local_ba_iterations, result->num_local_ba);
  }
  int outside_ignored = 0, outside_kept = 0;
  count_two_view(ignored, &outside_ignored);
  EXPECT_EQ(outside_ignored, 0);
  EXPECT_GT(count_two_view(kept, &outside_kept), 50);
  EXPECT_GT(outside_kept, 50);
  EXPECT_LT(ignored.reconstruction.NumPoints3D(), kept.reconstruction.NumPoints3D());
}

// A sparsely tracked video: no two frames share the 100 tracks an initial pair needs, so the
// strict search finds none; the relaxed search (COLMAP's halving) starts a model, and with
// relax_initial_pair off the result is kNoInitialPair, diagnosed by the strict search.
TEST(IncrementalPipeline, SparseTracksStartAModelAfterRelaxingTheInitialPair) {
  SyntheticSceneOptions scene_options;
  scene_options.motion = SyntheticMotion::kHandHeld;
  scene_options.num_frames = 12;
  scene_options.num_points = 90;
  scene_options.outlier_ratio = 0.05;
  const SyntheticScene scene = MakeSyntheticScene(scene_options);
  IncrementalPipelineOptions options;
  ASSERT_TRUE(options.relax_initial_pair);  // the default
  const IncrementalReconstruction relaxed =
      ReconstructIncrementally(scene.tracks, scene.camera, options);
  ASSERT_EQ(relaxed.status, ReconstructionStatus::kSuccess);
  EXPECT_GE(relaxed.registered_frames.size(), 10u);
  const auto evaluation = Evaluate(relaxed, scene);
  ASSERT_TRUE(evaluation.has_value());
  EXPECT_LT(evaluation->ate_fraction_of_path, 0.02);
  // The strict search's verdict is what a failure reports.
  EXPECT_EQ(relaxed.initial_pair_search.stage,
            IncrementalMapper::InitialPairSearch::Stage::kSharedTracks);

  options.relax_initial_pair = false;
  const IncrementalReconstruction strict =
      ReconstructIncrementally(scene.tracks, scene.camera, options);
  EXPECT_EQ(strict.status, ReconstructionStatus::kNoInitialPair);
  EXPECT_EQ(strict.initial_pair_search.stage,
            IncrementalMapper::InitialPairSearch::Stage::kSharedTracks);
}

TEST(IncrementalPipeline, PureRotationReportsNoInitialPair) {
  SyntheticSceneOptions scene_options;
  scene_options.motion = SyntheticMotion::kPureRotation;
  scene_options.num_frames = 15;
  const SyntheticScene scene = MakeSyntheticScene(scene_options);
  const IncrementalReconstruction result =
      ReconstructIncrementally(scene.tracks, scene.camera, IncrementalPipelineOptions());
  EXPECT_EQ(result.status, ReconstructionStatus::kNoInitialPair);
  EXPECT_EQ(result.reconstruction.NumRegisteredImages(), 0u);
  EXPECT_EQ(result.unregistered_frames.size(), 15u);
}

TEST(IncrementalPipeline, TwoFramesGiveAClearStatus) {
  SyntheticSceneOptions scene_options;
  scene_options.num_frames = 2;
  // Two frames 6 m apart: enough parallax for a two-view model.
  const SyntheticScene scene = MakeSyntheticScene(scene_options);
  const IncrementalReconstruction result =
      ReconstructIncrementally(scene.tracks, scene.camera, IncrementalPipelineOptions());
  EXPECT_EQ(result.status, ReconstructionStatus::kSuccess);
  EXPECT_EQ(result.registered_frames, (std::vector<int>{0, 1}));

  // Two frames from a rotating camera: nothing to triangulate.
  scene_options.motion = SyntheticMotion::kPureRotation;
  const SyntheticScene rotation = MakeSyntheticScene(scene_options);
  EXPECT_EQ(ReconstructIncrementally(rotation.tracks, rotation.camera, IncrementalPipelineOptions())
                .status,
            ReconstructionStatus::kNoInitialPair);

  // One frame, and no frame at all.
  scene_options.num_frames = 1;
  const SyntheticScene single = MakeSyntheticScene(scene_options);
  EXPECT_EQ(
      ReconstructIncrementally(single.tracks, single.camera, IncrementalPipelineOptions()).status,
      ReconstructionStatus::kTooFewFrames);
  frontend::FeatureTracks empty;
  EXPECT_EQ(ReconstructIncrementally(empty, single.camera, IncrementalPipelineOptions()).status,
            ReconstructionStatus::kTooFewFrames);
}

TEST(IncrementalPipeline, TooFewInitialPointsLeavesNoModel) {
  SyntheticSceneOptions scene_options;
  scene_options.num_frames = 6;
  scene_options.num_points = 200;
  const SyntheticScene scene = MakeSyntheticScene(scene_options);
  IncrementalPipelineOptions options;
  options.min_num_initial_points = 100000;
  options.max_num_models = 2;
  const IncrementalReconstruction result =
      ReconstructIncrementally(scene.tracks, scene.camera, options);
  EXPECT_EQ(result.status, ReconstructionStatus::kTooFewPoints);
  EXPECT_EQ(result.reconstruction.NumRegisteredImages(), 0u);
  EXPECT_EQ(result.reconstruction.NumPoints3D(), 0u);
  EXPECT_TRUE(result.registered_frames.empty());
  EXPECT_EQ(result.num_models, 2);
  EXPECT_NE(ReconstructionStatusMessage(result.status).find("too few points"), std::string::npos);
}

TEST(IncrementalPipeline, SameInputGivesIdenticalOutput) {
  SyntheticSceneOptions scene_options;
  scene_options.num_frames = 10;
  scene_options.num_points = 300;
  const SyntheticScene scene = MakeSyntheticScene(scene_options);
  const IncrementalReconstruction a =
      ReconstructIncrementally(scene.tracks, scene.camera, IncrementalPipelineOptions());
  const IncrementalReconstruction b =
      ReconstructIncrementally(scene.tracks, scene.camera, IncrementalPipelineOptions());
  ASSERT_EQ(a.status, ReconstructionStatus::kSuccess);
  ASSERT_EQ(a.reconstruction.NumPoints3D(), b.reconstruction.NumPoints3D());
  for (const auto& [image_id, image] : a.reconstruction.images()) {
    const Image& other = b.reconstruction.image(image_id);
    EXPECT_EQ(image.registered, other.registered);
    EXPECT_EQ(image.cam_from_world.translation, other.cam_from_world.translation);
    EXPECT_EQ(image.cam_from_world.rotation.coeffs(), other.cam_from_world.rotation.coeffs());
  }
  auto it = b.reconstruction.points3D().begin();
  for (const auto& [point3D_id, point] : a.reconstruction.points3D()) {
    EXPECT_EQ(point3D_id, it->first);
    EXPECT_EQ(point.xyz, it->second.xyz);
    ++it;
  }
}

TEST(IncrementalPipeline, RejectsInvalidOptions) {
  IncrementalPipelineOptions options;
  options.local_ba_num_images = 1;
  const SyntheticScene scene = MakeSyntheticScene(SyntheticSceneOptions());
  EXPECT_THROW(ReconstructIncrementally(scene.tracks, scene.camera, options), Error);
}

}  // namespace
}  // namespace comic::sfm
