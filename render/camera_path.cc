#include "render/camera_path.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

#include "io/core/error.h"
#include "io/core/file_utils.h"
#include "io/datasets/kitti_odometry.h"
#include "render/json_fields.h"
#include "render/random.h"

namespace comic::render {
namespace {

constexpr double kDeg = M_PI / 180.0;

// Streams of the shake's smooth noise.
enum ShakeStream : uint64_t { kHeight = 101, kLateral, kPitch, kYaw, kRoll };

Eigen::Vector3d Ground(const Eigen::Vector2d& xz, double y) { return {xz.x(), y, xz.y()}; }

std::shared_ptr<GroundTrack> ParseTrack(const JsonFields& fields) {
  auto track = std::make_shared<GroundTrack>(fields.Vector2("start", {0.0, 0.0}),
                                             fields.Number("heading_deg", 0.0));
  const nlohmann::json& segments = fields.At("segments");
  if (!segments.is_array() || segments.empty()) {
    fields.Fail("segments",
                "expected a list of {\"straight\": m} and {\"turn\": deg, \"radius\": m}");
  }
  for (size_t k = 0; k < segments.size(); ++k) {
    const JsonFields segment(segments[k], fields.where() + ": segments[" + std::to_string(k) + "]");
    segment.CheckKnown({"straight", "turn", "radius"});
    if (segment.Has("straight")) {
      track->AddStraight(segment.RequiredNumber("straight"));
    } else {
      track->AddTurn(segment.RequiredNumber("turn"), segment.RequiredNumber("radius"));
    }
  }
  if (fields.Bool("loop", false)) track->Close();
  return track;
}

// A scene names files beside it: a relative path without "..", so a scene from elsewhere cannot
// read (and quote in an error) any file the user can read.
bool IsInsideSceneFolder(const std::string& file) {
  if (file.empty() || file[0] == '/') return false;
  for (const auto& part : std::filesystem::path(file)) {
    if (part == "..") return false;
  }
  return true;
}

// KITTI's world is camera 0's frame (x right, y down, z forward); the scene's has y up and the
// ground at y = 0: turn half a revolution about z (x right stays right of +z forward) and lift
// by the camera's height.
std::vector<Pose> ReadPosesFile(const std::string& path, double height, int num_frames) {
  const std::vector<cv::Matx34d> world_from_cams = io::ReadKittiPoses(path);
  COMIC_CHECK(static_cast<int>(world_from_cams.size()) >= num_frames, kInvalidData,
              path << ": " << world_from_cams.size() << " poses for " << num_frames << " frames");
  const Eigen::Matrix3d flip = Eigen::Vector3d(-1.0, -1.0, 1.0).asDiagonal();
  std::vector<Pose> poses;
  for (const cv::Matx34d& m : world_from_cams) {
    Eigen::Matrix3d r;
    Eigen::Vector3d t;
    for (int i = 0; i < 3; ++i) {
      for (int j = 0; j < 3; ++j) r(i, j) = m(i, j);
      t(i) = m(i, 3);
    }
    const Eigen::Matrix3d world_rotation = flip * r;
    const Eigen::Vector3d center = flip * t + Eigen::Vector3d(0.0, height, 0.0);
    Pose pose;
    pose.rotation = world_rotation.transpose();
    pose.translation = -pose.rotation * center;
    poses.push_back(pose);
  }
  return poses;
}

}  // namespace

CameraPath CameraPath::FromJson(const nlohmann::json& json, const std::string& where,
                                const std::string& base_dir, int num_frames, uint64_t seed) {
  const JsonFields fields(json, where);
  CameraPath path;
  path.seed_ = seed;
  path.type_ = fields.RequiredString("type");
  if (fields.Has("shake")) {
    const JsonFields shake(fields.At("shake"), where + ": shake");
    shake.CheckKnown({"height", "lateral", "pitch_deg", "yaw_deg", "roll_deg", "period"});
    path.shake_.height = shake.Number("height", 0.0);
    path.shake_.lateral = shake.Number("lateral", 0.0);
    path.shake_.pitch = shake.Number("pitch_deg", 0.0) * kDeg;
    path.shake_.yaw = shake.Number("yaw_deg", 0.0) * kDeg;
    path.shake_.roll = shake.Number("roll_deg", 0.0) * kDeg;
    path.shake_.period = shake.Number("period", 12.0);
    if (!(path.shake_.period > 0)) shake.Fail("period", "must be > 0 frames");
  }
  path.height_ = fields.Number("height", 1.6);
  path.pitch_deg_ = fields.Number("pitch_deg", 0.0);
  if (path.type_ == "drive") {
    fields.CheckKnown({"type", "shake", "height", "pitch_deg", "start", "heading_deg", "segments",
                       "loop", "speed", "start_at", "lane_offset"});
    path.track_ = ParseTrack(fields);
    path.speed_ = fields.RequiredNumber("speed");
    path.start_ = fields.Number("start_at", 0.0);
    path.lane_offset_ = fields.Number("lane_offset", 0.0);
  } else if (path.type_ == "walk") {
    fields.CheckKnown({"type", "shake", "height", "pitch_deg", "start", "heading_deg", "speed",
                       "look_deg", "bob_amplitude", "bob_period"});
    path.speed_ = fields.RequiredNumber("speed");
    path.track_ = std::make_shared<GroundTrack>(fields.Vector2("start", {0.0, 0.0}),
                                                fields.Number("heading_deg", 0.0));
    path.track_->AddStraight(std::max(1.0, std::abs(path.speed_) * (num_frames + 1)));
    path.look_deg_ = fields.Number("look_deg", 90.0);
    path.bob_amplitude_ = fields.Number("bob_amplitude", 0.03);
    path.bob_period_ = fields.Number("bob_period", 18.0);
    if (!(path.bob_period_ > 0)) fields.Fail("bob_period", "must be > 0 frames");
  } else if (path.type_ == "orbit") {
    fields.CheckKnown({"type", "shake", "height", "pitch_deg", "center", "radius", "start_deg",
                       "degrees_per_frame", "look_at_height"});
    path.center_ = fields.Vector2("center", {0.0, 0.0});
    path.radius_ = fields.RequiredNumber("radius");
    if (!(path.radius_ > 0)) fields.Fail("radius", "must be > 0 m");
    path.start_ = fields.Number("start_deg", 0.0);
    path.speed_ = fields.RequiredNumber("degrees_per_frame");
    path.look_at_height_ = fields.Number("look_at_height", 1.0);
  } else if (path.type_ == "pan") {
    fields.CheckKnown(
        {"type", "shake", "height", "pitch_deg", "position", "start_deg", "degrees_per_frame"});
    path.center_ = fields.Vector2("position", {0.0, 0.0});
    path.start_ = fields.Number("start_deg", 0.0);
    path.speed_ = fields.RequiredNumber("degrees_per_frame");
  } else if (path.type_ == "poses") {
    fields.CheckKnown({"type", "shake", "height", "pitch_deg", "file"});
    const std::string file = fields.RequiredString("file");
    if (!IsInsideSceneFolder(file)) {
      fields.Fail("file",
                  "must be a path inside the scene's folder (relative, without \"..\"), got \"" +
                      file + "\"");
    }
    path.poses_ = ReadPosesFile(io::JoinPaths(base_dir, file), path.height_, num_frames);
  } else {
    fields.Fail("type", "unknown path \"" + path.type_ + "\" (drive, walk, orbit, pan or poses)");
  }
  if (path.speed_ == 0.0 && path.type_ != "poses") fields.Fail("speed", "must not be 0");
  return path;
}

Pose CameraPath::Shaken(const Pose& base, double time) const {
  if (shake_.height == 0 && shake_.lateral == 0 && shake_.pitch == 0 && shake_.yaw == 0 &&
      shake_.roll == 0) {
    return base;
  }
  const auto noise = [&](ShakeStream stream) {
    return SmoothNoise(seed_, stream, time, shake_.period);
  };
  // Offsets in the camera's own axes: sideways along its x axis, height along the world's up.
  const Eigen::Vector3d right = base.rotation.row(0).transpose();
  const Eigen::Vector3d center = base.Center() +
                                 shake_.height * noise(kHeight) * Eigen::Vector3d::UnitY() +
                                 shake_.lateral * noise(kLateral) * right;
  // Pitch up is about the camera's x axis (forward gains -y), yaw about its y axis.
  const Eigen::Matrix3d turn =
      (Eigen::AngleAxisd(shake_.roll * noise(kRoll), Eigen::Vector3d::UnitZ()) *
       Eigen::AngleAxisd(shake_.pitch * noise(kPitch), Eigen::Vector3d::UnitX()) *
       Eigen::AngleAxisd(shake_.yaw * noise(kYaw), Eigen::Vector3d::UnitY()))
          .toRotationMatrix();
  Pose pose;
  pose.rotation = turn.transpose() * base.rotation;
  pose.translation = -pose.rotation * center;
  return pose;
}

Pose CameraPath::At(double time) const {
  const double pitch = pitch_deg_ * kDeg;
  if (type_ == "poses") {
    const double t = std::clamp(time, 0.0, poses_.size() - 1.0);
    const size_t k = std::min(static_cast<size_t>(t), poses_.size() - 1);
    return Shaken(k + 1 < poses_.size() ? Interpolate(poses_[k], poses_[k + 1], t - k) : poses_[k],
                  time);
  }
  if (type_ == "drive") {
    const double a = start_ + speed_ * time;
    const Eigen::Vector2d p = track_->PointAt(a) - lane_offset_ * track_->LeftAt(a);
    const Eigen::Vector2d d = track_->DirectionAt(a);
    return Shaken(LookAlong(Ground(p, height_), Eigen::Vector3d(d.x(), 0.0, d.y()), pitch), time);
  }
  if (type_ == "walk") {
    const double a = speed_ * time;
    const Eigen::Vector2d p = track_->PointAt(a);
    const double heading = track_->HeadingAt(a) + look_deg_ * kDeg;
    // Bobbing: the head rises and falls once per step.
    const double bob = bob_amplitude_ * std::cos(2.0 * M_PI * time / bob_period_);
    return Shaken(LookAlong(Ground(p, height_ + bob),
                            Eigen::Vector3d(std::sin(heading), 0.0, std::cos(heading)), pitch),
                  time);
  }
  const double angle = (start_ + speed_ * time) * kDeg;
  if (type_ == "orbit") {
    const Eigen::Vector3d position =
        Ground(center_ + radius_ * Eigen::Vector2d(std::sin(angle), std::cos(angle)), height_);
    const Eigen::Vector3d forward = Ground(center_, look_at_height_) - position;
    const double elevation =
        std::atan2(forward.y(), Eigen::Vector2d(forward.x(), forward.z()).norm());
    return Shaken(
        LookAlong(position, Eigen::Vector3d(forward.x(), 0.0, forward.z()), elevation + pitch),
        time);
  }
  // pan
  return Shaken(LookAlong(Ground(center_, height_),
                          Eigen::Vector3d(std::sin(angle), 0.0, std::cos(angle)), pitch),
                time);
}

}  // namespace comic::render
