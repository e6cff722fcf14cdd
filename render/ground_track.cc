#include "render/ground_track.h"

#include <algorithm>
#include <cmath>

#include "io/core/error.h"

namespace comic::render {
namespace {

Eigen::Vector2d Direction(double heading) { return {std::sin(heading), std::cos(heading)}; }

// Point and heading `s` metres into a segment.
void Advance(const Eigen::Vector2d& start, double heading, double curvature, double s,
             Eigen::Vector2d* point, double* out_heading) {
  if (curvature == 0.0) {
    *point = start + s * Direction(heading);
    *out_heading = heading;
    return;
  }
  // With y up, +x lies to the left of +z, and heading 90 degrees is +x: turning left (positive
  // curvature) adds to the heading.
  const double end_heading = heading + curvature * s;
  // Integral of (sin h, cos h) dh / curvature from heading to end_heading.
  *point = start + Eigen::Vector2d(std::cos(heading) - std::cos(end_heading),
                                   std::sin(end_heading) - std::sin(heading)) /
                       curvature;
  *out_heading = end_heading;
}

}  // namespace

GroundTrack::GroundTrack(const Eigen::Vector2d& start, double heading_deg)
    : start_(start), start_heading_(heading_deg * M_PI / 180.0) {}

void GroundTrack::End(Eigen::Vector2d* point, double* heading) const {
  if (segments_.empty()) {
    *point = start_;
    *heading = start_heading_;
    return;
  }
  const Segment& last = segments_.back();
  Advance(last.start, last.start_heading, last.curvature, last.length, point, heading);
}

void GroundTrack::AddStraight(double length) {
  COMIC_CHECK(length > 0 && std::isfinite(length), kInvalidArgument,
              "track: a straight must be > 0 m long, got " << length);
  Segment segment;
  End(&segment.start, &segment.start_heading);
  segment.start_a = length_;
  segment.length = length;
  segments_.push_back(segment);
  length_ += length;
}

void GroundTrack::AddTurn(double angle_deg, double radius) {
  COMIC_CHECK(angle_deg != 0 && std::isfinite(angle_deg), kInvalidArgument,
              "track: a turn needs a non-zero angle");
  COMIC_CHECK(radius > 0 && std::isfinite(radius), kInvalidArgument,
              "track: a turn's radius must be > 0 m, got " << radius);
  Segment segment;
  End(&segment.start, &segment.start_heading);
  segment.start_a = length_;
  segment.length = std::abs(angle_deg) * M_PI / 180.0 * radius;
  segment.curvature = (angle_deg > 0 ? 1.0 : -1.0) / radius;
  segments_.push_back(segment);
  length_ += segment.length;
}

void GroundTrack::Close() {
  COMIC_CHECK(!segments_.empty(), kInvalidArgument, "track: a loop needs segments");
  Eigen::Vector2d end;
  double heading = 0.0;
  End(&end, &heading);
  const double gap = (end - start_).norm();
  double turn = std::remainder(heading - start_heading_, 2.0 * M_PI) * 180.0 / M_PI;
  COMIC_CHECK(gap <= 0.5 && std::abs(turn) <= 1.0, kInvalidArgument,
              "track: \"loop\" is set but the track ends " << gap << " m from its start, heading "
                                                           << turn
                                                           << " degrees off; adjust the segments");
  closed_ = true;
}

double GroundTrack::WrapArc(double a) const {
  if (closed_) {
    a = std::fmod(a, length_);
    return a < 0 ? a + length_ : a;
  }
  return std::clamp(a, 0.0, length_);
}

const GroundTrack::Segment& GroundTrack::SegmentAt(double a) const {
  auto it = std::upper_bound(segments_.begin(), segments_.end(), a,
                             [](double value, const Segment& s) { return value < s.start_a; });
  return it == segments_.begin() ? segments_.front() : *(it - 1);
}

Eigen::Vector2d GroundTrack::PointAt(double a) const {
  if (segments_.empty()) return start_;
  a = WrapArc(a);
  const Segment& segment = SegmentAt(a);
  Eigen::Vector2d point;
  double heading = 0.0;
  Advance(segment.start, segment.start_heading, segment.curvature, a - segment.start_a, &point,
          &heading);
  return point;
}

double GroundTrack::HeadingAt(double a) const {
  if (segments_.empty()) return start_heading_;
  a = WrapArc(a);
  const Segment& segment = SegmentAt(a);
  return segment.start_heading + segment.curvature * (a - segment.start_a);
}

Eigen::Vector2d GroundTrack::DirectionAt(double a) const { return Direction(HeadingAt(a)); }

Eigen::Vector2d GroundTrack::LeftAt(double a) const {
  const Eigen::Vector2d d = DirectionAt(a);
  return {d.y(), -d.x()};
}

}  // namespace comic::render
