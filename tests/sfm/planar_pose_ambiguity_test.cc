// A near-planar pair's two poses: the true one is either the essential matrix's or the other
// decomposition returned, and the third frames side with the true one; a general scene has no
// alternative; the options are checked.
#include "sfm/planar_pose_ambiguity.h"

#include <gtest/gtest.h>

#include <random>

#include "io/core/error.h"
#include "sfm/reconstruction.h"
#include "sfm/synthetic_scene.h"

namespace comic::sfm {
namespace {

struct Correspondences {
  Camera camera = Camera::FromImageSize(640, 480);
  std::vector<Eigen::Vector2d> points1, points2;
};

// Points on the tilted plane z = 10 + 0.3 x (or in a box 7..13 deep when not `planar`) seen from
// two poses, 0.3 px noise.
Correspondences Observe(const Rigid3d& cam1, const Rigid3d& cam2, bool planar, uint32_t seed) {
  Correspondences c;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(0, 1);
  std::normal_distribution<double> noise(0, 0.3);
  while (c.points1.size() < 300) {
    const double x = -4 + 8 * uniform(rng);
    const Eigen::Vector3d p(x, -3 + 6 * uniform(rng), planar ? 10 + 0.3 * x : 7 + 6 * uniform(rng));
    const auto x1 = ProjectPoint(c.camera, cam1, p);
    const auto x2 = ProjectPoint(c.camera, cam2, p);
    if (!x1 || !x2) continue;
    c.points1.push_back(*x1 + Eigen::Vector2d(noise(rng), noise(rng)));
    c.points2.push_back(*x2 + Eigen::Vector2d(noise(rng), noise(rng)));
  }
  return c;
}

TEST(PlanarPoseAmbiguity, ThePlanesTruePoseIsOneOfTheTwo) {
  const Rigid3d cam1 = LookAt({0, 0, 0}, {0, 0, 10});
  const Rigid3d cam2 = LookAt({1.8, 0.6, 0.4}, {0.2, 0.1, 10});
  const Rigid3d truth = cam2 * cam1.Inverse();
  int num_alternative_true = 0;
  for (uint32_t seed : {1u, 2u, 3u}) {
    const Correspondences c = Observe(cam1, cam2, true, seed);
    const TwoViewGeometry geometry =
        EstimateCalibratedTwoViewGeometry(c.camera, c.camera, c.points1, c.points2, {});
    ASSERT_NE(geometry.configuration, TwoViewConfiguration::kDegenerate);
    const auto other = OtherPlanarPose(c.camera, c.camera, c.points1, c.points2, geometry, 2.0, {});
    ASSERT_TRUE(other.has_value()) << "seed " << seed;
    // The two poses are the homography's two solutions, 11 deg apart here: the true one is
    // either the essential matrix's (within its precision on a plane, under 1 deg) or the
    // alternative (the homography's own solution, within 0.3 deg), never both.
    const double kept_error = RotationAngleDeg(geometry.cam2_from_cam1.rotation, truth.rotation);
    const double other_error = RotationAngleDeg(other->cam2_from_cam1.rotation, truth.rotation);
    EXPECT_NE(kept_error < 1.0, other_error < 0.3)
        << "seed " << seed << ": kept " << kept_error << " deg, other " << other_error << " deg";
    if (other_error < 0.3) {
      ++num_alternative_true;
      EXPECT_GT(other->num_inliers, 0.9 * 300);  // every point in front and reprojecting
    }
    EXPECT_GE(other->num_inliers, 0.5 * geometry.num_inliers);
    EXPECT_EQ(other->points3D.size(), static_cast<size_t>(other->num_inliers));
    EXPECT_EQ(other->triangulation_angles_deg.size(), other->points3D.size());
    EXPECT_EQ(other->inlier_mask.size(), c.points1.size());
    EXPECT_NEAR(other->cam2_from_cam1.translation.norm(), 1.0, 1e-9);
    for (const Eigen::Vector3d& p : other->points3D) EXPECT_GT(p.z(), 0.0);
    // Same input, same answer, bit for bit.
    const auto again = OtherPlanarPose(c.camera, c.camera, c.points1, c.points2, geometry, 2.0, {});
    ASSERT_TRUE(again.has_value());
    EXPECT_EQ(again->cam2_from_cam1.translation, other->cam2_from_cam1.translation);
    EXPECT_EQ(again->inlier_mask, other->inlier_mask);
  }
  // The case the alternative exists for: the essential matrix chose the wrong solution (seed 2).
  EXPECT_GE(num_alternative_true, 1);
}

// The tilted plane above filmed from eight places along a line (frame f at f * (0.6, 0.2, 0.13),
// all looking at the plane's middle), 0.3 px noise: one track per plane point.
frontend::FeatureTracks FilmThePlane(const Camera& camera, std::vector<Rigid3d>* poses,
                                     uint32_t seed) {
  frontend::FeatureTracks tracks;
  tracks.detector_name = "synthetic";
  tracks.image_size = cv::Size(camera.width, camera.height);
  const int num_frames = 8;
  for (int f = 0; f < num_frames; ++f) {
    poses->push_back(LookAt(Eigen::Vector3d(0.6, 0.2, 0.13) * f, {0.2, 0.1, 10}));
  }
  tracks.features.resize(num_frames);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(0, 1);
  std::normal_distribution<double> noise(0, 0.3);
  for (int i = 0; i < 400; ++i) {
    const double x = -4 + 8 * uniform(rng);
    const Eigen::Vector3d p(x, -3 + 6 * uniform(rng), 10 + 0.3 * x);
    frontend::Track track;
    for (int f = 0; f < num_frames; ++f) {
      const auto pixel = ProjectPoint(camera, (*poses)[f], p);
      if (!pixel) continue;
      frontend::Feature feature;
      feature.x = static_cast<float>(pixel->x() + noise(rng));
      feature.y = static_cast<float>(pixel->y() + noise(rng));
      track.observations.push_back({f, static_cast<int>(tracks.features[f].size())});
      tracks.features[f].push_back(feature);
    }
    if (track.Length() >= 2) tracks.tracks.push_back(track);
  }
  return tracks;
}

TEST(PlanarPoseAmbiguity, TheThirdFramesSideWithTheTruePose) {
  const Camera camera = Camera::FromImageSize(640, 480);
  const int frame1 = 0, frame2 = 3;
  for (uint32_t seed : {1u, 2u, 3u, 4u, 5u}) {
    std::vector<Rigid3d> poses;
    const frontend::FeatureTracks tracks = FilmThePlane(camera, &poses, seed);
    const Rigid3d truth = poses[frame2] * poses[frame1].Inverse();
    std::vector<int> track_ids;
    std::vector<Eigen::Vector2d> points1, points2;
    for (size_t t = 0; t < tracks.tracks.size(); ++t) {
      const auto& obs = tracks.tracks[t].observations;
      if (obs.size() < 8) continue;  // in every frame
      track_ids.push_back(static_cast<int>(t));
      const frontend::Feature& a = tracks.FeatureOf(obs[frame1]);
      const frontend::Feature& b = tracks.FeatureOf(obs[frame2]);
      points1.emplace_back(a.x, a.y);
      points2.emplace_back(b.x, b.y);
    }
    ASSERT_GT(track_ids.size(), 200u);
    const TwoViewGeometry essential =
        EstimateCalibratedTwoViewGeometry(camera, camera, points1, points2, {});
    const auto other = OtherPlanarPose(camera, camera, points1, points2, essential, 2.0, {});
    ASSERT_TRUE(other.has_value()) << "seed " << seed;
    const bool essential_true =
        RotationAngleDeg(essential.cam2_from_cam1.rotation, truth.rotation) < 1.0;
    const bool other_true = RotationAngleDeg(other->cam2_from_cam1.rotation, truth.rotation) < 1.0;
    ASSERT_NE(essential_true, other_true) << "seed " << seed;
    // Whichever pose is passed first, the third frames prefer the true one, clearly.
    const ThirdViewComparison forwards =
        CompareByThirdViews(tracks, camera, frame1, frame2, track_ids, essential, *other, {});
    const ThirdViewComparison backwards =
        CompareByThirdViews(tracks, camera, frame1, frame2, track_ids, *other, essential, {});
    EXPECT_EQ(forwards.prefers_second, other_true) << "seed " << seed;
    EXPECT_EQ(backwards.prefers_second, essential_true) << "seed " << seed;
    EXPECT_EQ(forwards.frames, (std::vector<int>{1, 2, 4, 5, 6, 7}));
    EXPECT_EQ(forwards.frame_median_error_first_px.size(), forwards.frames.size());
    const double true_error =
        other_true ? forwards.median_error_second_px : forwards.median_error_first_px;
    const double wrong_error =
        other_true ? forwards.median_error_first_px : forwards.median_error_second_px;
    EXPECT_LT(true_error, 0.7) << "seed " << seed;  // the noise, 0.3 px per coordinate
    EXPECT_GT(wrong_error, 1.4 * true_error) << "seed " << seed;
    // Same input, same answer, bit for bit.
    const ThirdViewComparison again =
        CompareByThirdViews(tracks, camera, frame1, frame2, track_ids, essential, *other, {});
    EXPECT_EQ(again.median_error_first_px, forwards.median_error_first_px);
    EXPECT_EQ(again.median_error_second_px, forwards.median_error_second_px);
  }
}

TEST(PlanarPoseAmbiguity, FramesTooFewToJudgeDecideNothing) {
  const Camera camera = Camera::FromImageSize(640, 480);
  std::vector<Rigid3d> poses;
  frontend::FeatureTracks tracks = FilmThePlane(camera, &poses, 2);
  // Only the pair's two frames see the tracks: no third frame, no preference.
  std::vector<int> track_ids;
  std::vector<Eigen::Vector2d> points1, points2;
  for (size_t t = 0; t < tracks.tracks.size(); ++t) {
    auto& obs = tracks.tracks[t].observations;
    if (obs.size() < 8) continue;
    obs = {obs[0], obs[3]};
    track_ids.push_back(static_cast<int>(t));
    points1.emplace_back(tracks.FeatureOf(obs[0]).x, tracks.FeatureOf(obs[0]).y);
    points2.emplace_back(tracks.FeatureOf(obs[1]).x, tracks.FeatureOf(obs[1]).y);
  }
  const TwoViewGeometry essential =
      EstimateCalibratedTwoViewGeometry(camera, camera, points1, points2, {});
  const auto other = OtherPlanarPose(camera, camera, points1, points2, essential, 2.0, {});
  ASSERT_TRUE(other.has_value());
  const ThirdViewComparison comparison =
      CompareByThirdViews(tracks, camera, 0, 3, track_ids, essential, *other, {});
  EXPECT_TRUE(comparison.frames.empty());
  EXPECT_FALSE(comparison.prefers_second);
  // Geometries of another pair's correspondences are refused.
  track_ids.pop_back();
  EXPECT_THROW(CompareByThirdViews(tracks, camera, 0, 3, track_ids, essential, *other, {}), Error);
}

TEST(PlanarPoseAmbiguity, AGeneralSceneHasNoAlternative) {
  const Rigid3d cam1 = LookAt({0, 0, 0}, {0, 0, 10});
  const Rigid3d cam2 = LookAt({1.8, 0.6, 0.4}, {0.2, 0.1, 10});
  const Correspondences c = Observe(cam1, cam2, false, 4);
  const TwoViewGeometry geometry =
      EstimateCalibratedTwoViewGeometry(c.camera, c.camera, c.points1, c.points2, {});
  ASSERT_EQ(geometry.configuration, TwoViewConfiguration::kCalibrated);
  EXPECT_FALSE(
      OtherPlanarPose(c.camera, c.camera, c.points1, c.points2, geometry, 2.0, {}).has_value());
}

TEST(PlanarPoseAmbiguity, BadOptionsAreRefused) {
  PlanarAmbiguityOptions options;
  options.min_homography_share = 0;
  EXPECT_THROW(options.Check(), Error);
  options = {};
  options.min_inlier_share = 1.5;
  EXPECT_THROW(options.Check(), Error);
  options = {};
  options.min_rotation_difference_deg = -1;
  EXPECT_THROW(options.Check(), Error);
  ThirdViewOptions third;
  third.min_pooled_error_reduction = 1.0;
  EXPECT_THROW(third.Check(), Error);
  third = {};
  third.min_frame_error_reduction = -0.1;
  EXPECT_THROW(third.Check(), Error);
  third = {};
  third.min_vote_ratio = 0.5;
  EXPECT_THROW(third.Check(), Error);
  third = {};
  third.max_views = 0;
  EXPECT_THROW(third.Check(), Error);
  third = {};
  third.min_shared_points = 3;
  EXPECT_THROW(third.Check(), Error);
}

}  // namespace
}  // namespace comic::sfm
