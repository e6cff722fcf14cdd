// Merging two models of one set of tracks (IncrementalMapper::MergeModel): a sparse ring that
// falls apart into models sharing a frame is joined with the right similarity, scale included,
// and a model whose points do not agree is refused.
#include <gtest/gtest.h>

#include <map>
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

// The scene's tracks with every track cut between frames `frame` and `frame` + 1, so that models
// on either side share neither a frame nor a track.
SyntheticScene CutTracks(SyntheticScene scene, int frame) {
  std::vector<frontend::Track> tracks;
  std::vector<int> points;
  for (size_t t = 0; t < scene.tracks.tracks.size(); ++t) {
    frontend::Track before, after;
    for (const frontend::TrackObservation& obs : scene.tracks.tracks[t].observations) {
      (obs.frame <= frame ? before : after).observations.push_back(obs);
    }
    for (frontend::Track* part : {&before, &after}) {
      if (part->Length() < 2) continue;
      tracks.push_back(std::move(*part));
      points.push_back(scene.track_point_index[t]);
    }
  }
  scene.tracks.tracks = std::move(tracks);
  scene.track_point_index = std::move(points);
  return scene;
}

TEST(ModelMerging, JoinsModelsSharingOnlyTracks) {
  const SyntheticScene scene = HandHeldScene();
  const int n = static_cast<int>(scene.cams_from_world.size());
  IncrementalMapper first(scene.tracks, scene.camera, IncrementalMapper::Options());
  IncrementalMapper second(scene.tracks, scene.camera, IncrementalMapper::Options());
  // No frame in common (frame 10 in neither), but the tracks running through frame 10 have
  // points in both models.
  GrowModel(&first, 0, 9, n);
  GrowModel(&second, 11, n - 1, n);
  ASSERT_EQ(first.MergeModel(second.reconstruction()), static_cast<size_t>(n - 11));
  const auto merged = Evaluate(first.reconstruction(), scene);
  ASSERT_TRUE(merged.has_value());
  EXPECT_LT(merged->ate_fraction_of_path, 0.01)
      << "ATE " << merged->ate_rmse << " over a path of " << merged->path_length;
}

TEST(ModelMerging, RefusesModelsWithoutSharedFrameOrAgreeingPoints) {
  {
    // No frame and no track in common.
    const SyntheticScene cut = CutTracks(HandHeldScene(), 10);
    const int n = static_cast<int>(cut.cams_from_world.size());
    IncrementalMapper first(cut.tracks, cut.camera, IncrementalMapper::Options());
    IncrementalMapper second(cut.tracks, cut.camera, IncrementalMapper::Options());
    GrowModel(&first, 0, 9, n);
    GrowModel(&second, 11, n - 1, n);
    EXPECT_EQ(first.MergeModel(second.reconstruction()), 0u);
  }
  const SyntheticScene scene = HandHeldScene();
  const int n = static_cast<int>(scene.cams_from_world.size());
  IncrementalMapper first(scene.tracks, scene.camera, IncrementalMapper::Options());
  GrowModel(&first, 0, 9, n);
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

// Models that share neither frames nor tracks are joined through links between their features
// (what matching the frames at the seam finds), and the linked points become one.
TEST(ModelMerging, JoinsModelsThroughFeatureLinks) {
  const SyntheticScene scene = CutTracks(HandHeldScene(), 10);
  const int n = static_cast<int>(scene.cams_from_world.size());
  IncrementalMapper first(scene.tracks, scene.camera, IncrementalMapper::Options());
  IncrementalMapper second(scene.tracks, scene.camera, IncrementalMapper::Options());
  GrowModel(&first, 0, 9, n);
  GrowModel(&second, 11, n - 1, n);
  ASSERT_EQ(first.MergeModel(second.reconstruction()), 0u);
  // Links between frame 9 (first) and frame 11 (second): the features of one scene point.
  std::map<int, int> feature_of_point_in_9, feature_of_point_in_11;
  for (size_t t = 0; t < scene.tracks.tracks.size(); ++t) {
    for (const frontend::TrackObservation& obs : scene.tracks.tracks[t].observations) {
      if (scene.is_outlier[obs.frame][obs.feature]) continue;
      if (obs.frame == 9) feature_of_point_in_9[scene.track_point_index[t]] = obs.feature;
      if (obs.frame == 11) feature_of_point_in_11[scene.track_point_index[t]] = obs.feature;
    }
  }
  std::vector<IncrementalMapper::FeatureLink> links;
  for (const auto& [point, feature] : feature_of_point_in_9) {
    const auto it = feature_of_point_in_11.find(point);
    if (it == feature_of_point_in_11.end()) continue;
    links.push_back({IncrementalMapper::ImageIdOfFrame(9), static_cast<point2D_t>(feature),
                     IncrementalMapper::ImageIdOfFrame(11), static_cast<point2D_t>(it->second)});
  }
  ASSERT_GT(links.size(), 50u);
  ASSERT_EQ(first.MergeModel(second.reconstruction(), links), static_cast<size_t>(n - 11));
  const auto merged = Evaluate(first.reconstruction(), scene);
  ASSERT_TRUE(merged.has_value());
  EXPECT_LT(merged->ate_fraction_of_path, 0.01)
      << "ATE " << merged->ate_rmse << " over a path of " << merged->path_length;
  // Linked features observe one point: seen from both sides of the cut.
  size_t num_joined = 0;
  for (const IncrementalMapper::FeatureLink& link : links) {
    const point3D_t a =
        first.reconstruction().image(link.image_id).points2D[link.point2D_idx].point3D_id;
    const point3D_t b = first.reconstruction()
                            .image(link.other_image_id)
                            .points2D[link.other_point2D_idx]
                            .point3D_id;
    num_joined += a != kInvalidPoint3DId && a == b;
  }
  EXPECT_GT(num_joined, links.size() / 3);
}

}  // namespace
}  // namespace comic::sfm
