// The line a drive or a walk follows on the ground, parametrised by arc length: straight runs and
// circular turns joined smoothly, as a scene file lists them. Street furniture is placed along it
// (scene_builder.h) and the camera moves along it (camera_path.h).
//
//   GroundTrack track({0, 0}, 0.0);   // starts at x = z = 0 heading along +z
//   track.AddStraight(50);            // metres
//   track.AddTurn(90, 12);            // degrees (positive: to the left), radius in metres
#pragma once

#include <Eigen/Core>
#include <vector>

namespace comic::render {

class GroundTrack {
 public:
  // Starts at `start` = (x, z) heading `heading_deg` (0 = along +z, 90 = along +x).
  GroundTrack(const Eigen::Vector2d& start, double heading_deg);

  // Throws comic::Error(kInvalidArgument) for a length or radius <= 0 or an angle of 0.
  void AddStraight(double length);
  void AddTurn(double angle_deg, double radius);

  double Length() const { return length_; }
  // Point (x, z), heading (radians) and unit direction (dx, dz) at arc length `a`, clamped to
  // [0, Length()] (or taken modulo Length() when `closed`).
  Eigen::Vector2d PointAt(double a) const;
  double HeadingAt(double a) const;
  Eigen::Vector2d DirectionAt(double a) const;
  // The unit normal to the left of the direction of travel.
  Eigen::Vector2d LeftAt(double a) const;

  // Makes the track a loop: arc length wraps around. Throws comic::Error(kInvalidArgument) saying
  // how far the end is from the start (must be within 0.5 m and 1 degree).
  void Close();
  bool closed() const { return closed_; }

 private:
  struct Segment {
    double start_a = 0.0;   // arc length where it starts
    double length = 0.0;    // metres
    Eigen::Vector2d start;  // (x, z)
    double start_heading = 0.0;
    double curvature = 0.0;  // 1/radius, signed (positive turns left); 0 = straight
  };
  double WrapArc(double a) const;
  const Segment& SegmentAt(double a) const;
  void End(Eigen::Vector2d* point, double* heading) const;

  Eigen::Vector2d start_;
  double start_heading_ = 0.0;
  std::vector<Segment> segments_;
  double length_ = 0.0;
  bool closed_ = false;
};

}  // namespace comic::render
