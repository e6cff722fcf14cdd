// Rigid and similarity transforms: composition, inverse, camera centre, and moving a pose with a
// similarity so that it still sees every point where it did.
#include "sfm/rigid3d.h"

#include <gtest/gtest.h>

namespace comic::sfm {
namespace {

Rigid3d MakePose(double angle, const Eigen::Vector3d& axis, const Eigen::Vector3d& translation) {
  return Rigid3d(Eigen::Quaterniond(Eigen::AngleAxisd(angle, axis.normalized())), translation);
}

TEST(Rigid3d, ComposeAndInvert) {
  const Rigid3d b_from_a = MakePose(0.3, {1, 2, 3}, {1, -2, 0.5});
  const Rigid3d c_from_b = MakePose(-1.1, {0, 1, 0}, {0.2, 0.1, 4});
  const Eigen::Vector3d x(0.7, -1.3, 2.2);
  EXPECT_TRUE(((c_from_b * b_from_a) * x).isApprox(c_from_b * (b_from_a * x), 1e-12));
  EXPECT_TRUE((b_from_a.Inverse() * (b_from_a * x)).isApprox(x, 1e-12));
  const Eigen::Matrix<double, 3, 4> m = b_from_a.ToMatrix();
  EXPECT_TRUE((m.leftCols<3>() * x + m.col(3)).isApprox(b_from_a * x, 1e-12));
}

TEST(Rigid3d, ProjectionCenterAndViewingDirection) {
  const Rigid3d cam_from_world = MakePose(0.8, {0.2, 1, 0.1}, {3, -1, 2});
  const Eigen::Vector3d center = ProjectionCenter(cam_from_world);
  EXPECT_LT((cam_from_world * center).norm(), 1e-12);
  // A point ahead along the viewing direction is on the optical axis.
  const Eigen::Vector3d ahead = cam_from_world * (center + 5.0 * ViewingDirection(cam_from_world));
  EXPECT_NEAR(ahead.x(), 0.0, 1e-12);
  EXPECT_NEAR(ahead.y(), 0.0, 1e-12);
  EXPECT_NEAR(ahead.z(), 5.0, 1e-12);
}

TEST(Rigid3d, RotationAngle) {
  const Eigen::Quaterniond a(Eigen::AngleAxisd(0.2, Eigen::Vector3d::UnitX()));
  const Eigen::Quaterniond b(Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitX()));
  EXPECT_NEAR(RotationAngleDeg(a, b), 0.3 * 180.0 / M_PI, 1e-9);
  // q and −q are the same rotation.
  EXPECT_NEAR(RotationAngleDeg(a, Eigen::Quaterniond(-a.coeffs())), 0.0, 1e-6);
}

TEST(Sim3d, TransformedPoseSeesTransformedPointsAlike) {
  Sim3d new_from_old;
  new_from_old.scale = 2.5;
  new_from_old.rotation =
      Eigen::Quaterniond(Eigen::AngleAxisd(1.0, Eigen::Vector3d(1, 1, 0).normalized()));
  new_from_old.translation = Eigen::Vector3d(4, -3, 1);
  const Rigid3d cam_from_old = MakePose(0.4, {0, 0, 1}, {0.5, 0.2, 3});
  const Rigid3d cam_from_new = new_from_old.TransformPose(cam_from_old);
  const Eigen::Vector3d point_old(0.3, -0.4, 2.0);
  const Eigen::Vector3d in_cam_old = cam_from_old * point_old;
  const Eigen::Vector3d in_cam_new = cam_from_new * (new_from_old * point_old);
  // Same ray (the camera frame is scaled with the world), so the same pixel.
  EXPECT_TRUE(in_cam_new.isApprox(new_from_old.scale * in_cam_old, 1e-12));
  EXPECT_TRUE(ProjectionCenter(cam_from_new)
                  .isApprox(new_from_old * ProjectionCenter(cam_from_old), 1e-12));
}

}  // namespace
}  // namespace comic::sfm
