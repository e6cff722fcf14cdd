// Ground truth as the SfM uses it: io's ground-truth cameras (io/datasets/ground_truth_cameras.h)
// matched to the frames of a run, as per-frame cam_from_world poses and a Camera at the frames'
// size; and any Reconstruction's poses (ours, or COLMAP's read back) matched to frames by image
// name, so both can go to EvaluateTrajectory.
//
//   const FrameGroundTruth truth = MatchGroundTruthToFrames(
//       io::ReadGroundTruthCameras(gt_path), sequence.FrameNames(), source_indices,
//       sequence.SourceFrameSize(), sequence.FrameSize());
//   const auto evaluation = EvaluateTrajectory(
//       RegisteredPosesByName(reconstruction, sequence.FrameNames()), truth.cams_from_world);
#pragma once

#include <Eigen/Core>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "io/datasets/ground_truth_cameras.h"
#include "sfm/camera.h"
#include "sfm/reconstruction.h"
#include "sfm/rigid3d.h"

namespace comic::sfm {

struct FrameGroundTruth {
  // Per frame of the run: the true cam_from_world, or std::nullopt if the file has none for it.
  std::vector<std::optional<Rigid3d>> cams_from_world;
  // The true intrinsics at the frames' (possibly resized) size, when the file gives them.
  std::optional<Camera> camera;
  int num_matched = 0;  // frames with a true pose
};

// A pinhole Camera from K (OpenCV pixel convention) for images of width x height. Throws
// comic::Error(kInvalidArgument) for skew or non-positive focal lengths.
Camera CameraFromK(const Eigen::Matrix3d& K, int width, int height);

// Matches ground-truth cameras to the frames of a run: by image name when the format names
// images (Middlebury, Strecha), by the nearest time stamp within the file's tolerance when it
// has time stamps (TUM, EuRoC) and every frame is named by its own ("1305031102.175304.png"),
// else by source frame index (KITTI: line i = source frame i).
// `source_size` is the size of the frames as stored, `frame_size` as used (resized); the
// intrinsics are scaled to it. Throws comic::Error(kInvalidData) when no frame matches, or the
// file states an image size different from `source_size`.
FrameGroundTruth MatchGroundTruthToFrames(const io::GroundTruthCameras& truth,
                                          const std::vector<std::string>& frame_names,
                                          const std::vector<int>& source_indices,
                                          const cv::Size& source_size, const cv::Size& frame_size);

// Per frame (matched by image name): the pose of the registered image of that name in
// `reconstruction`, or std::nullopt.
std::vector<std::optional<Rigid3d>> RegisteredPosesByName(
    const Reconstruction& reconstruction, const std::vector<std::string>& frame_names);

// Ground truth that does not cover every frame of the run is an error unless `allow_partial`
// (--gt-partial: evaluate on the frames it covers): throws comic::Error(kInvalidData) naming
// `path`, how many frames it covers and the first frame it misses (issue 19).
void CheckGroundTruthCoverage(const FrameGroundTruth& truth,
                              const std::vector<std::string>& frame_names, const std::string& path,
                              bool allow_partial);

}  // namespace comic::sfm
