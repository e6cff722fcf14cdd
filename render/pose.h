// A camera pose as the renderer uses it: cam_from_world (x_cam = rotation · x_world +
// translation), camera axes as OpenCV's (x right, y down, z forward). The world of the scenes has
// y up and the ground at y = 0 (scene_builder.h).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace comic::render {

struct Pose {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  Eigen::Vector3d Center() const { return -rotation.transpose() * translation; }
  Eigen::Vector3d CamFromWorld(const Eigen::Vector3d& x) const {
    return rotation * x + translation;
  }
};

// The camera at `center` looking along `forward` with the world's y axis up (roll 0); then
// turned by `pitch` (radians, positive looks up) and `roll` (radians, about the optical axis, x
// towards y) in its own axes. `forward` must not be vertical.
Pose LookAlong(const Eigen::Vector3d& center, const Eigen::Vector3d& forward, double pitch = 0.0,
               double roll = 0.0);

// The pose a fraction `w` in [0, 1] of the way from `a` to `b`: centres linearly, rotations by
// spherical interpolation.
Pose Interpolate(const Pose& a, const Pose& b, double w);

}  // namespace comic::render
