#include "sfm/rigid3d.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>

namespace comic::sfm {

Rigid3d::Rigid3d(const Eigen::Matrix3d& rotation_matrix, const Eigen::Vector3d& translation)
    : rotation(Eigen::Quaterniond(rotation_matrix).normalized()), translation(translation) {}

Rigid3d Rigid3d::operator*(const Rigid3d& b_from_a) const {
  return Rigid3d((rotation * b_from_a.rotation).normalized(),
                 rotation * b_from_a.translation + translation);
}

Rigid3d Rigid3d::Inverse() const {
  const Eigen::Quaterniond inverse_rotation = rotation.conjugate();
  return Rigid3d(inverse_rotation, -(inverse_rotation * translation));
}

Eigen::Matrix<double, 3, 4> Rigid3d::ToMatrix() const {
  Eigen::Matrix<double, 3, 4> matrix;
  matrix.leftCols<3>() = RotationMatrix();
  matrix.col(3) = translation;
  return matrix;
}

Eigen::Vector3d ProjectionCenter(const Rigid3d& cam_from_world) {
  return -(cam_from_world.rotation.conjugate() * cam_from_world.translation);
}

Eigen::Vector3d ViewingDirection(const Rigid3d& cam_from_world) {
  return cam_from_world.rotation.conjugate() * Eigen::Vector3d::UnitZ();
}

double RotationAngleDeg(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b) {
  // |w| of the relative rotation is cos(angle / 2); the absolute value folds q and −q together.
  const double w = std::abs((a.conjugate() * b).normalized().w());
  return 2.0 * std::acos(std::min(1.0, w)) * 180.0 / M_PI;
}

Eigen::Matrix3d ChordalMeanRotation(const std::vector<Eigen::Matrix3d>& rotations) {
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  for (const Eigen::Matrix3d& r : rotations) sum += r;
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(sum, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d d = Eigen::Matrix3d::Identity();
  d(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0 ? -1.0 : 1.0;
  return svd.matrixU() * d * svd.matrixV().transpose();
}

Rigid3d Sim3d::TransformPose(const Rigid3d& cam_from_world) const {
  // x_cam = R_c x_old + t_c and x_old = (R_s^T (x_new - t_s)) / s, so
  // x_cam · s = R_c R_s^T x_new + (s t_c - R_c R_s^T t_s); the camera frame is scaled by s.
  const Eigen::Quaterniond rotation_new =
      (cam_from_world.rotation * rotation.conjugate()).normalized();
  const Eigen::Vector3d translation_new =
      scale * cam_from_world.translation - rotation_new * translation;
  return Rigid3d(rotation_new, translation_new);
}

}  // namespace comic::sfm
