// PnP RANSAC: the pose is recovered despite wrong correspondences, too little support gives no
// pose, and the result is deterministic.
#include "sfm/absolute_pose.h"

#include <gtest/gtest.h>

#include <random>

#include "io/core/error.h"
#include "sfm/reconstruction.h"
#include "sfm/synthetic_scene.h"

namespace comic::sfm {
namespace {

struct Correspondences {
  Camera camera = Camera::FromImageSize(640, 480);
  Rigid3d truth = LookAt({1, -0.5, -2}, {0, 0, 8});
  std::vector<Eigen::Vector2d> points2D;
  std::vector<Eigen::Vector3d> points3D;
  std::vector<bool> outlier;
};

Correspondences Observe(int n, double outlier_ratio, uint32_t seed) {
  Correspondences c;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(0, 1);
  std::normal_distribution<double> noise(0, 0.5);
  while (static_cast<int>(c.points3D.size()) < n) {
    const Eigen::Vector3d p(-3 + 6 * uniform(rng), -2 + 4 * uniform(rng), 5 + 6 * uniform(rng));
    const auto x = ProjectPoint(c.camera, c.truth, p);
    if (!x || x->x() < 0 || x->y() < 0 || x->x() > 639 || x->y() > 479) continue;
    const bool outlier = uniform(rng) < outlier_ratio;
    c.points3D.push_back(p);
    c.points2D.push_back(outlier ? Eigen::Vector2d(640 * uniform(rng), 480 * uniform(rng))
                                 : *x + Eigen::Vector2d(noise(rng), noise(rng)));
    c.outlier.push_back(outlier);
  }
  return c;
}

TEST(AbsolutePose, RecoversPoseDespiteOutliers) {
  const Correspondences c = Observe(200, 0.3, 7);
  const auto pose = EstimateAbsolutePose(c.camera, c.points2D, c.points3D, {});
  ASSERT_TRUE(pose.has_value());
  EXPECT_LT(RotationAngleDeg(pose->cam_from_world.rotation, c.truth.rotation), 0.2);
  EXPECT_LT((ProjectionCenter(pose->cam_from_world) - ProjectionCenter(c.truth)).norm(), 0.05);
  int outliers_kept = 0, true_kept = 0;
  for (size_t i = 0; i < c.outlier.size(); ++i) {
    outliers_kept += c.outlier[i] && pose->inlier_mask[i];
    true_kept += !c.outlier[i] && pose->inlier_mask[i];
  }
  EXPECT_LT(outliers_kept, 5);
  EXPECT_GT(true_kept, 120);
  EXPECT_EQ(pose->num_inliers, outliers_kept + true_kept);
  const auto again = EstimateAbsolutePose(c.camera, c.points2D, c.points3D, {});
  ASSERT_TRUE(again.has_value());
  EXPECT_EQ(again->cam_from_world.translation, pose->cam_from_world.translation);
  EXPECT_EQ(again->inlier_mask, pose->inlier_mask);
}

TEST(AbsolutePose, TooLittleSupportGivesNoPose) {
  const Correspondences few = Observe(10, 0.0, 8);
  EXPECT_FALSE(EstimateAbsolutePose(few.camera, few.points2D, few.points3D, {}).has_value());
  // 90 % wrong: below the minimum inlier ratio.
  const Correspondences noise = Observe(200, 0.9, 9);
  EXPECT_FALSE(EstimateAbsolutePose(noise.camera, noise.points2D, noise.points3D, {}).has_value());
  EXPECT_THROW(EstimateAbsolutePose(few.camera, few.points2D, {}, {}), Error);
  AbsolutePoseOptions bad;
  bad.min_num_inliers = 3;
  EXPECT_THROW(bad.Check(), Error);
}

}  // namespace
}  // namespace comic::sfm
