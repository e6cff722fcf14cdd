#include "frontend/evaluation/epipolar_check.h"

#include <gtest/gtest.h>

#include <cmath>

#include "io/datasets/kitti_odometry.h"
#include "tests/test_support.h"

namespace comic::frontend {
namespace {

cv::Point2f Project(const cv::Matx33d& K, const cv::Matx34d& world_from_camera,
                    const cv::Vec3d& point_in_world) {
  const cv::Matx33d r = world_from_camera.get_minor<3, 3>(0, 0);
  const cv::Vec3d t(world_from_camera(0, 3), world_from_camera(1, 3), world_from_camera(2, 3));
  const cv::Vec3d in_camera = r.t() * (point_in_world - t);
  const cv::Vec3d pixel = K * in_camera;
  return {static_cast<float>(pixel[0] / pixel[2]), static_cast<float>(pixel[1] / pixel[2])};
}

TEST(EpipolarCheck, ProjectionsOfOnePointAreOnEachOthersLines) {
  const cv::Matx33d K(700, 0, 600, 0, 700, 180, 0, 0, 1);
  // Camera b: 1.2 m forward, 0.1 m right, turned by 2 degrees about y.
  const double angle = 2.0 * M_PI / 180.0;
  const cv::Matx34d a(1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0);
  const cv::Matx34d b(std::cos(angle), 0, std::sin(angle), 0.1, 0, 1, 0, 0, -std::sin(angle), 0,
                      std::cos(angle), 1.2);
  const cv::Matx33d F = FundamentalFromPoses(K, a, b);
  for (const cv::Vec3d& point :
       {cv::Vec3d(-3, 1, 10), cv::Vec3d(4, -1, 25), cv::Vec3d(0.5, 0, 7)}) {
    const cv::Point2f pa = Project(K, a, point);
    const cv::Point2f pb = Project(K, b, point);
    EXPECT_LT(EpipolarDistance(F, pa, pb), 1e-3);
    // Moving the second point 3 px across the line shows up as 3 px.
    const cv::Vec3d line = F * cv::Vec3d(pa.x, pa.y, 1);
    const cv::Point2f normal(static_cast<float>(line[0] / std::hypot(line[0], line[1])),
                             static_cast<float>(line[1] / std::hypot(line[0], line[1])));
    EXPECT_NEAR(EpipolarDistance(F, pa, pb + 3.0f * normal), 3.0, 1e-3);
    EXPECT_LT(EpipolarDistance(F, pa, pb + 3.0f * cv::Point2f(-normal.y, normal.x)), 1e-3);
  }
  FeatureSet fa(1), fb(2);
  fa[0].x = Project(K, a, {1, 1, 12}).x, fa[0].y = Project(K, a, {1, 1, 12}).y;
  fb[0].x = Project(K, b, {1, 1, 12}).x, fb[0].y = Project(K, b, {1, 1, 12}).y;
  const cv::Vec3d line = F * cv::Vec3d(fa[0].x, fa[0].y, 1);
  fb[1].x = fb[0].x + static_cast<float>(5 * line[0] / std::hypot(line[0], line[1]));
  fb[1].y = fb[0].y + static_cast<float>(5 * line[1] / std::hypot(line[0], line[1]));
  const std::vector<bool> ok = EpipolarConsistency(F, fa, fb, {{0, 0, 0.f}, {0, 1, 0.f}}, 1.0);
  EXPECT_EQ(ok, (std::vector<bool>{true, false}));
}

TEST(EpipolarCheck, ScaledIntrinsicsMapPixelAreas) {
  const cv::Matx33d K(707.0912, 0, 601.8873, 0, 707.0912, 183.1104, 0, 0, 1);
  const cv::Matx33d half = ScaleIntrinsics(K, {1226, 370}, {613, 185});
  EXPECT_DOUBLE_EQ(half(0, 0), 707.0912 / 2);
  EXPECT_DOUBLE_EQ(half(0, 2), (601.8873 + 0.5) / 2 - 0.5);
  EXPECT_DOUBLE_EQ(half(1, 2), (183.1104 + 0.5) / 2 - 0.5);
}

TEST(EpipolarCheck, KittiPosesMakeAFundamentalMatrixOfRankTwo) {
  const auto poses = io::ReadKittiPoses(test::ExampleDir() + "/poses.txt");
  const cv::Matx33d K = io::ReadKittiIntrinsics(test::ExampleDir() + "/calib.txt");
  const cv::Matx33d F = FundamentalFromPoses(K, poses[0], poses[1]);
  EXPECT_NEAR(cv::determinant(F) / std::pow(cv::norm(F), 3), 0.0, 1e-9);
  // Forward motion: the epipole (F e = 0) lies near the principal point.
  cv::Mat w, u, vt;
  cv::SVD::compute(cv::Mat(F), w, u, vt);
  const cv::Mat e = vt.row(2);
  const double ex = e.at<double>(0) / e.at<double>(2);
  const double ey = e.at<double>(1) / e.at<double>(2);
  EXPECT_NEAR(ex, K(0, 2), 60.0);
  EXPECT_NEAR(ey, K(1, 2), 60.0);
}

}  // namespace
}  // namespace comic::frontend
