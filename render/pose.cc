#include "render/pose.h"

#include <cmath>

namespace comic::render {

Pose LookAlong(const Eigen::Vector3d& center, const Eigen::Vector3d& forward, double pitch,
               double roll) {
  const Eigen::Vector3d f = forward.normalized();
  const Eigen::Vector3d right = f.cross(Eigen::Vector3d::UnitY()).normalized();
  const Eigen::Vector3d down = f.cross(right);
  Eigen::Matrix3d level;
  level.row(0) = right.transpose();
  level.row(1) = down.transpose();
  level.row(2) = f.transpose();
  // Pitching up turns the camera about its x axis so that its forward axis gains -y (up).
  const Eigen::Matrix3d turn = (Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitZ()) *
                                Eigen::AngleAxisd(pitch, Eigen::Vector3d::UnitX()))
                                   .toRotationMatrix();
  Pose pose;
  pose.rotation = turn.transpose() * level;
  pose.translation = -pose.rotation * center;
  return pose;
}

Pose Interpolate(const Pose& a, const Pose& b, double w) {
  const Eigen::Quaterniond qa(a.rotation);
  const Eigen::Quaterniond qb(b.rotation);
  const Eigen::Vector3d center = (1.0 - w) * a.Center() + w * b.Center();
  Pose pose;
  pose.rotation = qa.slerp(w, qb).normalized().toRotationMatrix();
  pose.translation = -pose.rotation * center;
  return pose;
}

}  // namespace comic::render
