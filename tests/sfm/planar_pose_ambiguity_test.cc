// A near-planar pair's two poses: the true one is either the essential matrix's or the other
// decomposition returned; a general scene has no alternative; the options are checked.
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
}

}  // namespace
}  // namespace comic::sfm
