// The mapping engine's steps on synthetic tracks: initial pair under forward motion, exclusions,
// registration, filtering.
#include "sfm/incremental_mapper.h"

#include <gtest/gtest.h>

#include "io/error.h"
#include "sfm/synthetic_scene.h"

namespace comic::sfm {
namespace {

SyntheticScene ForwardScene() {
  SyntheticSceneOptions options;
  options.motion = SyntheticMotion::kForward;
  options.num_frames = 16;
  options.num_points = 700;
  options.seed = 21;
  return MakeSyntheticScene(options);
}

TEST(IncrementalMapper, FindsAnInitialPairUnderForwardMotion) {
  const SyntheticScene scene = ForwardScene();
  const IncrementalMapper mapper(scene.tracks, scene.camera, IncrementalMapper::Options());
  const auto pair = mapper.FindInitialPair();
  ASSERT_TRUE(pair.has_value());
  EXPECT_EQ(pair->geometry.configuration, TwoViewConfiguration::kCalibrated);
  EXPECT_GE(pair->score, IncrementalMapper::Options().init_min_score);
  // Forward motion: most points lie near the epipole, so the median triangulation angle is far
  // below COLMAP's 16 degree initial-pair threshold; the parallax score still finds the pair.
  EXPECT_LT(pair->geometry.median_triangulation_angle_deg, 16.0);
  EXPECT_GT(pair->image_id2, pair->image_id1);
  // Candidates come best first.
  const auto pairs = mapper.FindInitialPairs();
  ASSERT_FALSE(pairs.empty());
  for (size_t i = 1; i < pairs.size(); ++i) EXPECT_GE(pairs[i - 1].score, pairs[i].score);
  // Excluded frames take no part.
  std::set<image_t> excluded = {pair->image_id1, pair->image_id2};
  const auto other = mapper.FindInitialPair(excluded);
  ASSERT_TRUE(other.has_value());
  EXPECT_FALSE(excluded.count(other->image_id1));
  EXPECT_FALSE(excluded.count(other->image_id2));
}

TEST(IncrementalMapper, RegistersTriangulatesAndFilters) {
  const SyntheticScene scene = ForwardScene();
  IncrementalMapper mapper(scene.tracks, scene.camera, IncrementalMapper::Options());
  const auto pair = mapper.FindInitialPair();
  ASSERT_TRUE(pair.has_value());
  const size_t num_points = mapper.RegisterInitialPair(*pair);
  EXPECT_GT(num_points, 100u);
  EXPECT_EQ(mapper.reconstruction().NumRegisteredImages(), 2u);
  EXPECT_THROW(mapper.RegisterInitialPair(*pair), Error);  // only once
  mapper.AdjustGlobalBundle(BundleAdjustmentOptions());
  const std::vector<image_t> candidates = mapper.NextImageCandidates();
  ASSERT_FALSE(candidates.empty());
  for (image_t id : candidates) EXPECT_FALSE(mapper.reconstruction().image(id).registered);
  ASSERT_TRUE(mapper.RegisterNextImage(candidates[0]));
  EXPECT_GT(mapper.last_num_pose_inliers(), 30);
  EXPECT_THROW(mapper.RegisterNextImage(candidates[0]), Error);  // already registered
  EXPECT_GT(mapper.TriangulateImage(candidates[0]), 0u);
  const BundleAdjustmentSummary local =
      mapper.AdjustLocalBundle(candidates[0], BundleAdjustmentOptions(), 3);
  EXPECT_TRUE(local.usable);
  EXPECT_LE(local.num_variable_images, 3);
  EXPECT_EQ(mapper.registration_order().size(), 3u);

  // Filtering keeps what is consistent...
  const size_t before = mapper.reconstruction().NumObservations();
  EXPECT_EQ(mapper.FilterPoints(), 0u);
  EXPECT_EQ(mapper.reconstruction().NumObservations(), before);
}

TEST(IncrementalMapper, FilterRemovesLargeErrorsAndSmallAngles) {
  const SyntheticScene scene = ForwardScene();
  // ... and removes what its thresholds reject: with 0.5 px noise, a 0.05 px limit rejects nearly
  // every observation; a 60 degree minimum angle every point.
  IncrementalMapper::Options strict_error;
  strict_error.filter_max_reprojection_error_px = 0.05;
  IncrementalMapper mapper(scene.tracks, scene.camera, strict_error);
  const auto pair = mapper.FindInitialPair();
  ASSERT_TRUE(pair.has_value());
  const size_t num_points = mapper.RegisterInitialPair(*pair);
  ASSERT_GT(num_points, 100u);
  EXPECT_GT(mapper.FilterPoints(), num_points);
  EXPECT_LT(mapper.reconstruction().NumPoints3D(), num_points / 4);

  IncrementalMapper::Options strict_angle;
  strict_angle.filter_min_tri_angle_deg = 60;
  IncrementalMapper angle_mapper(scene.tracks, scene.camera, strict_angle);
  angle_mapper.RegisterInitialPair(*pair);
  EXPECT_EQ(angle_mapper.FilterPoints(), 2 * num_points);
  EXPECT_EQ(angle_mapper.reconstruction().NumPoints3D(), 0u);
}

TEST(IncrementalMapper, ImageIdsAreFramesPlusOne) {
  EXPECT_EQ(IncrementalMapper::ImageIdOfFrame(0), 1u);
  EXPECT_EQ(IncrementalMapper::FrameOfImageId(12), 11);
  const SyntheticScene scene = ForwardScene();
  const IncrementalMapper mapper(scene.tracks, scene.camera, IncrementalMapper::Options());
  EXPECT_EQ(mapper.reconstruction().NumImages(), 16u);
  EXPECT_EQ(mapper.reconstruction().image(1).name, "000000.png");
  EXPECT_EQ(mapper.reconstruction().image(1).points2D.size(), scene.tracks.features[0].size());
  IncrementalMapper::Options bad;
  bad.init_tri_angle_deg = 0;
  EXPECT_THROW(IncrementalMapper(scene.tracks, scene.camera, bad), Error);
}

}  // namespace
}  // namespace comic::sfm
