// Rigid and similarity transforms between coordinate frames, named after what they map, as COLMAP
// does: `cam_from_world * point3D_in_world` is the point in camera coordinates.
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <vector>

namespace comic::sfm {

// x_b = R · x_a + t for b_from_a.
struct Rigid3d {
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();  // unit quaternion
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();         // in the target frame's units

  Rigid3d() = default;
  Rigid3d(const Eigen::Quaterniond& rotation, const Eigen::Vector3d& translation)
      : rotation(rotation), translation(translation) {}
  // From a rotation matrix (must be orthonormal with det +1) and a translation.
  Rigid3d(const Eigen::Matrix3d& rotation_matrix, const Eigen::Vector3d& translation);

  Eigen::Vector3d operator*(const Eigen::Vector3d& point) const {
    return rotation * point + translation;
  }
  // Composition: (c_from_b * b_from_a) maps a to c.
  Rigid3d operator*(const Rigid3d& b_from_a) const;

  Rigid3d Inverse() const;
  Eigen::Matrix3d RotationMatrix() const { return rotation.toRotationMatrix(); }
  // [R | t], 3x4.
  Eigen::Matrix<double, 3, 4> ToMatrix() const;
};

// For a cam_from_world pose: the camera centre in world coordinates, −Rᵀt.
Eigen::Vector3d ProjectionCenter(const Rigid3d& cam_from_world);

// For a cam_from_world pose: the viewing direction (the camera's +z axis) in world coordinates.
Eigen::Vector3d ViewingDirection(const Rigid3d& cam_from_world);

// Angle in degrees of the rotation taking `a` to `b` (0..180).
double RotationAngleDeg(const Eigen::Quaterniond& a, const Eigen::Quaterniond& b);

// The rotation closest (Frobenius) to the mean of `rotations`: their chordal L2 mean (the
// identity for none).
Eigen::Matrix3d ChordalMeanRotation(const std::vector<Eigen::Matrix3d>& rotations);

// x_b = s · R · x_a + t for b_from_a.
struct Sim3d {
  double scale = 1.0;
  Eigen::Quaterniond rotation = Eigen::Quaterniond::Identity();
  Eigen::Vector3d translation = Eigen::Vector3d::Zero();

  Eigen::Vector3d operator*(const Eigen::Vector3d& point) const {
    return scale * (rotation * point) + translation;
  }
  // Maps a cam_from_world pose of the source world to the cam_from_world pose of the same camera
  // in the target world (the camera centre moves with the points; the scale cancels in rotation).
  Rigid3d TransformPose(const Rigid3d& cam_from_world) const;
};

}  // namespace comic::sfm
