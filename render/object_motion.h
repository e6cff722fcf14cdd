// How an object moves: rigidly, at a constant velocity and a constant yaw rate about a vertical
// axis through its pivot. Time is in frames (frame k is at time k, motion-blur sub-frames lie
// between), and the scene as built is the scene at time 0, so a static scene is one whose objects
// all have the default (no) motion. What stands still for the camera's path but not for SfM:
// features on such an object fit no camera's epipolar geometry.
#pragma once

#include <Eigen/Core>

namespace comic::render {

struct ObjectMotion {
  Eigen::Vector3d velocity = Eigen::Vector3d::Zero();  // metres per frame
  // Radians per frame, a right-handed turn about +y (up): z turns towards x.
  double yaw_rate = 0.0;
  Eigen::Vector3d pivot = Eigen::Vector3d::Zero();  // a point on the turning axis at time 0

  bool Moves() const { return !velocity.isZero(0.0) || yaw_rate != 0.0; }
  // Where a point of the object at time 0 is at `time`.
  Eigen::Vector3d PointAt(const Eigen::Vector3d& point, double time) const;
  // Where a direction (a piece's axis) of the object at time 0 points at `time`.
  Eigen::Vector3d DirectionAt(const Eigen::Vector3d& direction, double time) const;

  // Throws comic::Error(kInvalidArgument): a value not finite, a speed over 100 m per frame or a
  // turn over half a turn per frame (sub-frames could not tell which way it went).
  void Check() const;
};

}  // namespace comic::render
