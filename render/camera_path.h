// Where the camera is at each moment of a sequence, from a scene file's "path":
//   drive   along a GroundTrack of straights and turns (optionally a loop), at a lane offset
//   walk    sideways handheld walk: a straight line, the camera looking off to one side, bobbing
//   orbit   around a centre, looking at it
//   pan     turning on the spot (no parallax)
//   poses   a KITTI poses.txt (camera-to-world per frame), set on the ground of the scene
// Every path takes an optional "shake" (smooth random height, sideways, pitch, yaw and roll
// offsets), seeded by the scene's seed. Time is in frames and may be fractional (motion blur).
//
//   CameraPath path = CameraPath::FromJson(scene["path"], "scene.json: path", "scenes/", 500, 7);
//   Pose pose = path.At(12.0);  // cam_from_world of frame 12
#pragma once

#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "render/ground_track.h"
#include "render/pose.h"

namespace comic::render {

class CameraPath {
 public:
  // `where` names the path in messages; relative file names resolve against `base_dir`;
  // `num_frames` bounds a walk's track and is checked against a poses file's length. Throws
  // comic::Error: kInvalidArgument naming the field, kNotFound / kInvalidData for a poses file.
  static CameraPath FromJson(const nlohmann::json& json, const std::string& where,
                             const std::string& base_dir, int num_frames, uint64_t seed);

  // cam_from_world at `time` (frames).
  Pose At(double time) const;
  // The line on the ground a drive or walk follows (street furniture is placed along it);
  // nullptr for an orbit, a pan or poses.
  const GroundTrack* track() const { return track_.get(); }
  const std::string& type() const { return type_; }

 private:
  struct Shake {
    double height = 0.0;  // metres (amplitude)
    double lateral = 0.0;
    double pitch = 0.0;  // radians
    double yaw = 0.0;
    double roll = 0.0;
    double period = 12.0;  // frames between the noise's knots
  };
  // `base` moved and turned by the shake at `time`.
  Pose Shaken(const Pose& base, double time) const;

  std::string type_;
  uint64_t seed_ = 0;
  Shake shake_;
  std::shared_ptr<GroundTrack> track_;
  // drive / walk / orbit / pan parameters
  double speed_ = 0.0;        // metres (drive, walk) or degrees (orbit, pan) per frame
  double height_ = 1.6;       // camera above the ground, metres
  double start_ = 0.0;        // arc length (drive) or angle in degrees (orbit, pan)
  double lane_offset_ = 0.0;  // drive: metres to the right of the track
  double pitch_deg_ = 0.0;
  double look_deg_ = 90.0;      // walk: view direction relative to the motion, positive to the left
  double bob_amplitude_ = 0.0;  // walk: metres
  double bob_period_ = 18.0;    // walk: frames per step
  Eigen::Vector2d center_{0.0, 0.0};  // orbit centre, pan position (x, z)
  double radius_ = 10.0;              // orbit
  double look_at_height_ = 1.0;       // orbit
  std::vector<Pose> poses_;           // poses: cam_from_world per frame, in the scene's world
};

}  // namespace comic::render
