// Merging two models of one set of tracks (IncrementalMapper::MergeModel): a sparse ring that
// falls apart into models sharing a frame is joined with the right similarity, scale included,
// and a model whose points do not agree is refused.
#include <gtest/gtest.h>

#include <random>
#include <set>

#include "sfm/evaluation/ground_truth.h"
#include "sfm/incremental_mapper.h"
#include "sfm/synthetic_scene.h"
#include "sfm/trajectory_evaluation.h"

namespace comic::sfm {
namespace {

SyntheticScene HandHeldScene() {
  SyntheticSceneOptions options;
  options.motion = SyntheticMotion::kHandHeld;
  options.num_frames = 20;
  options.num_points = 800;
  options.seed = 7;
  return MakeSyntheticScene(options);
}

// Grows a model on the frames [first, last] only (as the pipeline does on the whole set).
void GrowModel(IncrementalMapper* mapper, int first, int last, int num_frames) {
  std::set<image_t> excluded;
  for (int frame = 0; frame < num_frames; ++frame) {
    if (frame < first || frame > last) excluded.insert(IncrementalMapper::ImageIdOfFrame(frame));
  }
  const auto pair = mapper->FindInitialPair(excluded);
  ASSERT_TRUE(pair.has_value());
  ASSERT_GT(mapper->RegisterInitialPair(*pair), 30u);
  mapper->AdjustGlobalBundle(BundleAdjustmentOptions());
  bool registered = true;
  while (registered) {
    registered = false;
    for (image_t image_id : mapper->NextImageCandidates()) {
      if (excluded.count(image_id) || !mapper->RegisterNextImage(image_id)) continue;
      mapper->TriangulateImage(image_id);
      mapper->AdjustLocalBundle(image_id, BundleAdjustmentOptions(), 6);
      registered = true;
      break;
    }
  }
  mapper->AdjustGlobalBundle(BundleAdjustmentOptions());
  ASSERT_EQ(mapper->reconstruction().NumRegisteredImages(), static_cast<size_t>(last - first + 1));
}

std::optional<TrajectoryEvaluation> Evaluate(const Reconstruction& reconstruction,
                                             const SyntheticScene& scene) {
  return EvaluateTrajectory(RegisteredPosesByName(reconstruction, scene.tracks.frame_names),
                            {scene.cams_from_world.begin(), scene.cams_from_world.end()});
}

TEST(ModelMerging, JoinsModelsSharingOneFrameWithTheRightScale) {
  const SyntheticScene scene = HandHeldScene();
  const int n = static_cast<int>(scene.cams_from_world.size());
  IncrementalMapper first(scene.tracks, scene.camera, IncrementalMapper::Options());
  IncrementalMapper second(scene.tracks, scene.camera, IncrementalMapper::Options());
  // Frames 0-10 and 10-19: frame 10 is the only one both register. Each model has its own
  // gauge (origin, orientation and scale of its initial pair).
  GrowModel(&first, 0, 10, n);
  GrowModel(&second, 10, n - 1, n);

  ASSERT_EQ(first.MergeModel(second.reconstruction()), static_cast<size_t>(n - 11));
  EXPECT_EQ(first.reconstruction().NumRegisteredImages(), static_cast<size_t>(n));
  // The mapped poses are right before any adjustment: one shared frame fixes rotation and
  // translation, the shared points the scale (a wrong scale moves every merged camera).
  const auto merged = Evaluate(first.reconstruction(), scene);
  ASSERT_TRUE(merged.has_value());
  EXPECT_LT(merged->ate_fraction_of_path, 0.01)
      << "ATE " << merged->ate_rmse << " over a path of " << merged->path_length;
  EXPECT_LT(merged->mean_rotation_error_deg, 0.5);
  // Tracks seen on both sides of frame 10 got points from both sides' frames.
  size_t num_spanning = 0;
  for (const auto& [id, point] : first.reconstruction().points3D()) {
    bool before = false, after = false;
    for (const TrackElement& element : point.track) {
      const int frame = IncrementalMapper::FrameOfImageId(element.image_id);
      before |= frame < 10;
      after |= frame > 10;
    }
    num_spanning += before && after;
  }
  EXPECT_GT(num_spanning, 50u);
  // Nothing left to merge.
  EXPECT_EQ(first.MergeModel(second.reconstruction()), 0u);
}

TEST(ModelMerging, RefusesModelsWithoutSharedFrameOrAgreeingPoints) {
  const SyntheticScene scene = HandHeldScene();
  const int n = static_cast<int>(scene.cams_from_world.size());
  IncrementalMapper first(scene.tracks, scene.camera, IncrementalMapper::Options());
  GrowModel(&first, 0, 9, n);
  {
    // No frame in common.
    IncrementalMapper second(scene.tracks, scene.camera, IncrementalMapper::Options());
    GrowModel(&second, 11, n - 1, n);
    EXPECT_EQ(first.MergeModel(second.reconstruction()), 0u);
  }
  // Frames in common, but the other model's points are scrambled: no similarity maps them.
  IncrementalMapper second(scene.tracks, scene.camera, IncrementalMapper::Options());
  GrowModel(&second, 8, n - 1, n);
  Reconstruction scrambled = second.reconstruction();
  std::mt19937 random(3);
  std::normal_distribution<double> noise(0.0, 1.0);
  for (const auto& [id, point] : second.reconstruction().points3D()) {
    scrambled.point3D(id).xyz += Eigen::Vector3d(noise(random), noise(random), noise(random));
  }
  EXPECT_EQ(first.MergeModel(scrambled), 0u);
  EXPECT_EQ(first.reconstruction().NumRegisteredImages(), 10u);
  // The same model unscrambled is merged.
  EXPECT_EQ(first.MergeModel(second.reconstruction()), static_cast<size_t>(n - 10));
}

}  // namespace
}  // namespace comic::sfm
