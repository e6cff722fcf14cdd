// --intrinsics FILE as a camera of the frames as used: the file describes the frames as stored
// (io/datasets/camera_calibration_file.h: 'fx fy cx cy [k1 k2 p1 p2]', a 3x3 K or a 3x4 P such as
// KITTI's calib.txt, an OpenCV FileStorage YAML/XML calibration or a COLMAP cameras.txt; OpenCV
// pixel convention), and a resized sequence scales it (pixel centre c -> (c + 0.5) s - 0.5,
// sfm::Camera::Scaled; distortion acts on normalised coordinates and stays).
// --camera-model NAME picks the model (sfm/camera_model.h) of the default camera, or converts
// the file's camera to it where that loses nothing.
#pragma once

#include <opencv2/core/types.hpp>
#include <optional>
#include <string>

#include "sfm/camera.h"

namespace comic::apps {

// Throws comic::Error for a missing or malformed file, a file made for another image size or a
// camera `model` cannot hold.
sfm::Camera LoadCameraIntrinsics(const std::string& path, const cv::Size& source_size,
                                 const cv::Size& frame_size,
                                 const std::optional<sfm::CameraModelId>& model = std::nullopt);

// The model named by --camera-model; throws comic::Error(kInvalidArgument) listing the names.
sfm::CameraModelId ParseCameraModelFlag(const std::string& name);

// `camera` as `model` when that loses nothing (a one-focal model needs fx == fy; the target must
// hold every non-zero distortion coefficient); throws comic::Error(kInvalidArgument) otherwise.
sfm::Camera ConvertCameraModel(const sfm::Camera& camera, sfm::CameraModelId model);

}  // namespace comic::apps
