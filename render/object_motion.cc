#include "render/object_motion.h"

#include <Eigen/Geometry>
#include <cmath>

#include "io/core/error.h"

namespace comic::render {
namespace {

constexpr double kMaxSpeed = 100.0;  // metres per frame

}  // namespace

Eigen::Vector3d ObjectMotion::DirectionAt(const Eigen::Vector3d& direction, double time) const {
  if (yaw_rate == 0.0) return direction;
  return Eigen::AngleAxisd(yaw_rate * time, Eigen::Vector3d::UnitY()) * direction;
}

Eigen::Vector3d ObjectMotion::PointAt(const Eigen::Vector3d& point, double time) const {
  return pivot + DirectionAt(point - pivot, time) + velocity * time;
}

void ObjectMotion::Check() const {
  COMIC_CHECK(velocity.allFinite() && pivot.allFinite() && std::isfinite(yaw_rate),
              kInvalidArgument, "object motion: velocity, yaw rate and pivot must be finite");
  COMIC_CHECK(
      velocity.norm() <= kMaxSpeed, kInvalidArgument,
      "object motion: speed must be <= " << kMaxSpeed << " m per frame, got " << velocity.norm());
  COMIC_CHECK(
      std::abs(yaw_rate) <= M_PI, kInvalidArgument,
      "object motion: yaw rate must be within half a turn (pi rad) per frame, got " << yaw_rate);
}

}  // namespace comic::render
