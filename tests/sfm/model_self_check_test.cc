#include "sfm/model_self_check.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <vector>

#include "io/core/error.h"
#include "sfm/incremental_pipeline.h"
#include "sfm/synthetic_scene.h"

namespace comic::sfm {
namespace {

SyntheticScene HandHeldScene() {
  SyntheticSceneOptions options;
  options.motion = SyntheticMotion::kHandHeld;
  options.num_frames = 20;
  options.num_points = 800;
  return MakeSyntheticScene(options);
}

// A model of `scene` with the given cameras: every frame registered, every track's true point
// triangulated from its inlier observations (image i + 1 is frame i, as the mapper numbers them).
Reconstruction ModelWithCameras(const SyntheticScene& scene,
                                const std::vector<Rigid3d>& cams_from_world) {
  Reconstruction model;
  const camera_t camera_id = model.AddCamera(scene.camera);
  for (size_t frame = 0; frame < scene.tracks.NumFrames(); ++frame) {
    Image image;
    image.image_id = static_cast<image_t>(frame + 1);
    image.camera_id = camera_id;
    image.name = "frame" + std::to_string(frame);
    image.cam_from_world = cams_from_world[frame];
    for (const frontend::Feature& feature : scene.tracks.features[frame]) {
      Point2D point;
      point.xy = Eigen::Vector2d(feature.x, feature.y);
      image.points2D.push_back(point);
    }
    model.AddImage(image);
    model.RegisterImage(image.image_id);
  }
  for (size_t t = 0; t < scene.tracks.tracks.size(); ++t) {
    std::vector<TrackElement> track;
    for (const frontend::TrackObservation& obs : scene.tracks.tracks[t].observations) {
      if (scene.is_outlier[obs.frame][obs.feature]) continue;
      track.push_back({static_cast<image_t>(obs.frame + 1), static_cast<point2D_t>(obs.feature)});
    }
    if (track.size() >= 2) model.AddPoint3D(scene.points3D[scene.track_point_index[t]], track);
  }
  return model;
}

// Turns every camera from `first` on by `degrees` about its own centre: the model of a run that
// went wrong half-way, whose later cameras still see their points nearly where they were.
std::vector<Rigid3d> TurnedFrom(const std::vector<Rigid3d>& cams_from_world, size_t first,
                                double degrees) {
  std::vector<Rigid3d> turned = cams_from_world;
  const Eigen::Quaterniond turn(
      Eigen::AngleAxisd(degrees * M_PI / 180.0, Eigen::Vector3d(0.3, 1.0, 0.2).normalized()));
  for (size_t frame = first; frame < turned.size(); ++frame) {
    const Eigen::Vector3d center = cams_from_world[frame].Inverse().translation;
    turned[frame].rotation = turn * cams_from_world[frame].rotation;
    turned[frame].translation = -(turned[frame].rotation * center);
  }
  return turned;
}

TEST(ModelSelfCheck, TheTrueCamerasExplainEveryPair) {
  const SyntheticScene scene = HandHeldScene();
  const ModelSelfCheck check = CheckModelAgainstItsPairs(
      ModelWithCameras(scene, scene.cams_from_world), scene.tracks, ModelSelfCheckOptions());
  EXPECT_GE(check.pairs_checked, 20);
  EXPECT_EQ(check.pairs_disagreeing, 0);
  EXPECT_TRUE(check.disagreeing.empty());
  EXPECT_FALSE(check.suspect);
  EXPECT_TRUE(check.reason.empty());
  EXPECT_LT(check.median_rotation_difference_deg, 1.0);
}

TEST(ModelSelfCheck, CamerasTurnedHalfWayAreSuspect) {
  const SyntheticScene scene = HandHeldScene();
  const std::vector<Rigid3d> turned = TurnedFrom(scene.cams_from_world, 10, 5.0);
  const ModelSelfCheck check = CheckModelAgainstItsPairs(ModelWithCameras(scene, turned),
                                                         scene.tracks, ModelSelfCheckOptions());
  EXPECT_GE(check.pairs_checked, 20);
  // The pairs across the turn disagree; those on either side of it agree.
  EXPECT_GT(check.pairs_disagreeing, 0);
  EXPECT_LT(check.pairs_disagreeing, check.pairs_checked);
  EXPECT_TRUE(check.suspect);
  EXPECT_NE(check.reason.find("not explained by the model"), std::string::npos) << check.reason;
  // Each disagreeing pair is named, and each straddles the turn at frame 10.
  ASSERT_EQ(check.disagreeing.size(), static_cast<size_t>(check.pairs_disagreeing));
  for (const DisagreeingPair& pair : check.disagreeing) {
    EXPECT_LT(std::min(pair.frame1, pair.frame2), 10);
    EXPECT_GE(std::max(pair.frame1, pair.frame2), 10);
    EXPECT_GT(pair.error_ratio, ModelSelfCheckOptions().max_error_ratio);
    EXPECT_GT(pair.inliers, 0);
    EXPECT_GE(pair.shared_tracks, pair.inliers);
  }
}

TEST(ModelSelfCheck, TooFewPairsSayNothing) {
  const SyntheticScene scene = HandHeldScene();
  ModelSelfCheckOptions options;
  options.min_pairs = 1000;
  const ModelSelfCheck check = CheckModelAgainstItsPairs(
      ModelWithCameras(scene, TurnedFrom(scene.cams_from_world, 10, 5.0)), scene.tracks, options);
  EXPECT_GT(check.pairs_disagreeing, 0);
  EXPECT_FALSE(check.suspect);
}

TEST(ModelSelfCheck, ASmallTurnWithinTheErrorBoundIsNotSuspect) {
  const SyntheticScene scene = HandHeldScene();
  const ModelSelfCheck check = CheckModelAgainstItsPairs(
      ModelWithCameras(scene, TurnedFrom(scene.cams_from_world, 10, 0.05)), scene.tracks,
      ModelSelfCheckOptions());
  EXPECT_FALSE(check.suspect) << check.reason;
}

TEST(ModelSelfCheck, ThePipelineCallsAWrongModelSuspectNotSuccess) {
  // The pipeline's own model of a clean scene passes its check.
  const SyntheticScene scene = HandHeldScene();
  const IncrementalReconstruction result =
      ReconstructIncrementally(scene.tracks, scene.camera, IncrementalPipelineOptions());
  EXPECT_EQ(result.status, ReconstructionStatus::kSuccess);
  EXPECT_GE(result.self_check.pairs_checked, 20);
  EXPECT_FALSE(result.self_check.suspect);
  EXPECT_STREQ(ReconstructionStatusName(ReconstructionStatus::kSuspect), "suspect");
  EXPECT_TRUE(HasModel(ReconstructionStatus::kSuspect));
}

// `model` with its frames from `first_unregistered` on taken out.
Reconstruction WithoutFramesFrom(Reconstruction model, size_t first_unregistered) {
  for (image_t id = static_cast<image_t>(first_unregistered + 1); model.ExistsImage(id); ++id) {
    model.DeRegisterImage(id);
  }
  return model;
}

TEST(ModelSelfCheck, ANearlyAsLargeModelItsPairsDoNotContradictIsKeptFirst) {
  const SyntheticScene scene = HandHeldScene();
  const Reconstruction wrong =
      ModelWithCameras(scene, TurnedFrom(scene.cams_from_world, 10, 5.0));  // 20 frames
  const Reconstruction right =
      WithoutFramesFrom(ModelWithCameras(scene, scene.cams_from_world), 17);  // 17 frames
  ASSERT_EQ(right.NumRegisteredImages(), 17u);
  const KeptModelChoice choice =
      ChooseKeptModel({&wrong, &right}, scene.tracks, ModelSelfCheckOptions(), 0.8);
  EXPECT_EQ(choice.index, 1u);
  EXPECT_FALSE(choice.check.suspect) << choice.check.reason;
  EXPECT_EQ(choice.check.passed_over_model_frames, 20);
  EXPECT_GT(choice.check.passed_over_pairs_disagreeing, 0);
  // Not nearly as large (17 of 20 frames is below 0.9): the larger model stays first, suspect.
  const KeptModelChoice kept =
      ChooseKeptModel({&wrong, &right}, scene.tracks, ModelSelfCheckOptions(), 0.9);
  EXPECT_EQ(kept.index, 0u);
  EXPECT_TRUE(kept.check.suspect);
  EXPECT_EQ(kept.check.passed_over_model_frames, 0);
}

TEST(ModelSelfCheck, ASuspectModelIsKeptWhenTheOthersAreSuspectToo) {
  const SyntheticScene scene = HandHeldScene();
  const Reconstruction wrong = ModelWithCameras(scene, TurnedFrom(scene.cams_from_world, 10, 5.0));
  const Reconstruction also_wrong =
      ModelWithCameras(scene, TurnedFrom(scene.cams_from_world, 6, -5.0));
  const KeptModelChoice choice =
      ChooseKeptModel({&wrong, &also_wrong}, scene.tracks, ModelSelfCheckOptions(), 0.8);
  EXPECT_EQ(choice.index, 0u);
  EXPECT_TRUE(choice.check.suspect);
  // A right first model is kept whatever follows it.
  const Reconstruction right = ModelWithCameras(scene, scene.cams_from_world);
  const KeptModelChoice first =
      ChooseKeptModel({&right, &wrong}, scene.tracks, ModelSelfCheckOptions(), 0.8);
  EXPECT_EQ(first.index, 0u);
  EXPECT_FALSE(first.check.suspect);
  EXPECT_THROW(ChooseKeptModel({}, scene.tracks, ModelSelfCheckOptions(), 0.8), Error);
}

TEST(ModelSelfCheck, BadOptionsAreRefused) {
  ModelSelfCheckOptions options;
  options.max_error_ratio = 0.5;
  EXPECT_THROW(options.Check(), Error);
  options = ModelSelfCheckOptions();
  options.min_shared_tracks = 2;
  EXPECT_THROW(options.Check(), Error);
  options = ModelSelfCheckOptions();
  options.min_disagreeing_pairs = 0;
  EXPECT_THROW(options.Check(), Error);
  IncrementalPipelineOptions pipeline;
  pipeline.self_check_yield_fraction = 0.0;
  EXPECT_THROW(pipeline.Check(), Error);
  pipeline.self_check_yield_fraction = 1.5;
  EXPECT_THROW(pipeline.Check(), Error);
}

}  // namespace
}  // namespace comic::sfm
