// Ground-truth trajectories of the SLAM benchmarks, one pose per time stamp:
//
//   TUM RGB-D (and what `evo` writes): "timestamp tx ty tz qx qy qz qw" per line, '#' comments;
//     (tx, ty, tz) the camera centre, (qx, qy, qz, qw) the camera-to-world rotation (scalar
//     last); time stamps in seconds.
//   EuRoC MAV groundtruth/data.csv: a "#timestamp, p_RS_R_x [m], ..." header, then per line
//     "timestamp, px, py, pz, qw, qx, qy, qz, ..." (comma separated, scalar first, velocities and
//     biases after); time stamps in nanoseconds. The pose is the body's (the IMU's) in the world,
//     not the camera's: the camera sits a few centimetres and a fixed turn away from it
//     (sensor.yaml's T_BS), which a Sim(3)-aligned position error hardly sees; the rotations are
//     those of the body.
//
// Each line becomes a GroundTruthCamera with its index (0, 1, ... in file order) and time stamp,
// no image name and no intrinsics; sfm/evaluation/ground_truth.h matches them to frames by time
// stamp when the frames are named by theirs (TUM's rgb/1305031102.175304.png, EuRoC's
// cam0/data/1403636579763555584.png), else line i to frame i.
//
//   const GroundTruthCameras truth =
//   ReadTumTrajectory("rgbd_dataset_freiburg1_xyz/groundtruth.txt");
#pragma once

#include <string>

#include "io/datasets/ground_truth_cameras.h"

namespace comic::io {

// The frames' time stamps and the file's may differ by this much and still match: 20 ms, the
// max_difference of TUM's associate.py (TUM's ground truth runs at 100 Hz, EuRoC's at 200 Hz).
inline constexpr double kTumTimestampTolerance = 0.02;          // seconds
inline constexpr double kEurocTimestampTolerance = 0.02 * 1e9;  // nanoseconds

// Whether `text` (a file's contents) looks like either format: its first line that is not blank
// or a '#' comment is 8 numbers (TUM); its first line is EuRoC's header, or its first data line
// is at least 8 comma-separated numbers (EuRoC).
bool LooksLikeTumTrajectory(const std::string& text);
bool LooksLikeEurocGroundTruth(const std::string& text);

// Read `path`. Throws comic::Error: kNotFound for a missing file, kInvalidData naming the file and
// line for a line of another width, a field that is not a number, or a quaternion whose norm is
// not 1 (within 1e-3; it is normalised).
GroundTruthCameras ReadTumTrajectory(const std::string& path);
GroundTruthCameras ReadEurocGroundTruth(const std::string& path);

}  // namespace comic::io
