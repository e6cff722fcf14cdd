// Relative pose from two calibrated views: recovered with outliers, flagged for rotation-only and
// planar scenes, degenerate for too few matches, deterministic.
#include "sfm/two_view_geometry.h"

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
  std::vector<bool> outlier;
};

// Points in a box (or on the plane z = 10 when `planar`) seen from two poses; a fraction of the
// second view's points replaced by random pixels; 0.3 px noise.
Correspondences Observe(const Rigid3d& cam1, const Rigid3d& cam2, bool planar, double outlier_ratio,
                        uint32_t seed) {
  Correspondences c;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> uniform(0, 1);
  std::normal_distribution<double> noise(0, 0.3);
  while (c.points1.size() < 300) {
    const Eigen::Vector3d p(-4 + 8 * uniform(rng), -3 + 6 * uniform(rng),
                            planar ? 10.0 : 7 + 6 * uniform(rng));
    const auto x1 = ProjectPoint(c.camera, cam1, p);
    const auto x2 = ProjectPoint(c.camera, cam2, p);
    if (!x1 || !x2) continue;
    const bool outlier = uniform(rng) < outlier_ratio;
    c.points1.push_back(*x1 + Eigen::Vector2d(noise(rng), noise(rng)));
    c.points2.push_back(outlier ? Eigen::Vector2d(640 * uniform(rng), 480 * uniform(rng))
                                : *x2 + Eigen::Vector2d(noise(rng), noise(rng)));
    c.outlier.push_back(outlier);
  }
  return c;
}

TEST(TwoViewGeometry, RecoversRelativePoseDespiteOutliers) {
  const Rigid3d cam1 = LookAt({0, 0, 0}, {0, 0, 10});
  const Rigid3d cam2 = LookAt({1.5, 0.2, 0.3}, {0.3, 0, 10});
  const Correspondences c = Observe(cam1, cam2, false, 0.2, 3);
  const TwoViewGeometry geometry =
      EstimateCalibratedTwoViewGeometry(c.camera, c.camera, c.points1, c.points2, {});
  ASSERT_EQ(geometry.configuration, TwoViewConfiguration::kCalibrated);
  const Rigid3d truth = cam2 * cam1.Inverse();
  EXPECT_LT(RotationAngleDeg(geometry.cam2_from_cam1.rotation, truth.rotation), 0.2);
  const double direction_error_deg =
      std::acos(std::clamp(geometry.cam2_from_cam1.translation.dot(truth.translation.normalized()),
                           -1.0, 1.0)) *
      180 / M_PI;
  EXPECT_LT(direction_error_deg, 2.0);
  EXPECT_NEAR(geometry.cam2_from_cam1.translation.norm(), 1.0, 1e-9);
  // Inliers: nearly all true correspondences, hardly any outlier.
  int true_kept = 0, outliers_kept = 0, num_true = 0;
  for (size_t i = 0; i < c.outlier.size(); ++i) {
    num_true += !c.outlier[i];
    true_kept += !c.outlier[i] && geometry.inlier_mask[i];
    outliers_kept += c.outlier[i] && geometry.inlier_mask[i];
  }
  EXPECT_GT(true_kept, 0.9 * num_true);
  EXPECT_LT(outliers_kept, 5);
  EXPECT_EQ(geometry.num_inliers, true_kept + outliers_kept);
  EXPECT_EQ(geometry.points3D.size(), static_cast<size_t>(geometry.num_inliers));
  EXPECT_EQ(geometry.triangulation_angles_deg.size(), geometry.points3D.size());
  EXPECT_GT(geometry.median_triangulation_angle_deg, 3.0);
  for (const Eigen::Vector3d& p : geometry.points3D) EXPECT_GT(p.z(), 0.0);

  // Same input, same answer, bit for bit.
  const TwoViewGeometry again =
      EstimateCalibratedTwoViewGeometry(c.camera, c.camera, c.points1, c.points2, {});
  EXPECT_EQ(again.inlier_mask, geometry.inlier_mask);
  EXPECT_EQ(again.cam2_from_cam1.translation, geometry.cam2_from_cam1.translation);
}

TEST(TwoViewGeometry, RotationOnlyAndPlanarScenesAreFlagged) {
  const Rigid3d cam1 = LookAt({0, 0, 0}, {0, 0, 10});
  const Correspondences rotation = Observe(cam1, LookAt({0, 0, 0}, {2, 0.5, 10}), false, 0.0, 4);
  EXPECT_EQ(EstimateCalibratedTwoViewGeometry(rotation.camera, rotation.camera, rotation.points1,
                                              rotation.points2, {})
                .configuration,
            TwoViewConfiguration::kPlanarOrPanoramic);
  const Correspondences planar = Observe(cam1, LookAt({1.5, 0, 0}, {0, 0, 10}), true, 0.0, 5);
  EXPECT_EQ(EstimateCalibratedTwoViewGeometry(planar.camera, planar.camera, planar.points1,
                                              planar.points2, {})
                .configuration,
            TwoViewConfiguration::kPlanarOrPanoramic);
}

TEST(TwoViewGeometry, TooFewMatchesAreDegenerate) {
  const Correspondences c =
      Observe(LookAt({0, 0, 0}, {0, 0, 10}), LookAt({1, 0, 0}, {0, 0, 10}), false, 0.0, 6);
  const std::vector<Eigen::Vector2d> few1(c.points1.begin(), c.points1.begin() + 10);
  const std::vector<Eigen::Vector2d> few2(c.points2.begin(), c.points2.begin() + 10);
  const TwoViewGeometry geometry =
      EstimateCalibratedTwoViewGeometry(c.camera, c.camera, few1, few2, {});
  EXPECT_EQ(geometry.configuration, TwoViewConfiguration::kDegenerate);
  EXPECT_EQ(geometry.inlier_mask.size(), 10u);
  EXPECT_THROW(EstimateCalibratedTwoViewGeometry(c.camera, c.camera, few1, c.points2, {}), Error);
  TwoViewGeometryOptions bad;
  bad.confidence = 1.0;
  EXPECT_THROW(EstimateCalibratedTwoViewGeometry(c.camera, c.camera, c.points1, c.points2, bad),
               Error);
}

}  // namespace
}  // namespace comic::sfm
