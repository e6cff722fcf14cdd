// Which camera a run uses, decided once for the command line and Python alike:
//   1. --intrinsics FILE: the file describes the frames as stored
//      (io/datasets/camera_calibration_file.h: 'fx fy cx cy [k1 k2 p1 p2]', a 3x3 K or a 3x4 P
//      such as KITTI's calib.txt, an OpenCV FileStorage YAML/XML calibration or a COLMAP
//      cameras.txt; OpenCV pixel convention); a resized sequence scales it (pixel centre
//      c -> (c + 0.5) s - 0.5, Camera::Scaled; distortion acts on normalised coordinates and
//      stays);
//   2. else the ground truth's intrinsics (--gt), unless --ignore-gt-intrinsics;
//   3. else COLMAP's default for an unknown camera, SIMPLE_RADIAL with the principal point at the
//      centre and k = 0, which the run self-calibrates: the focal length and distortion are
//      refined (COLMAP's ba_refine_focal_length and ba_refine_extra_params) unless
//      --fixed-intrinsics. Its focal length is the one the photos' EXIF states when the frames
//      read agree (exif_focal_prior.h), else f = 1.2 max(w, h).
// --camera-model NAME picks the model (sfm/camera_model.h) of the default camera, or converts a
// file's or the ground truth's camera to it where that loses nothing.
//
//   CameraChoice choice;  choice.intrinsics = "calib.txt";
//   ResolvedCamera camera = ResolveCamera(choice, source_size, frame_size, ground_truth, gt);
#pragma once

#include <opencv2/core/types.hpp>
#include <optional>
#include <string>

#include "sfm/camera.h"
#include "sfm/evaluation/ground_truth.h"
#include "sfm/run/exif_focal_prior.h"

namespace comic::sfm {

// The options that choose the camera, by comic_sfm's flag names.
struct CameraChoice {
  std::string intrinsics;             // --intrinsics FILE (empty: none)
  std::string camera_model;           // --camera-model NAME (empty: SIMPLE_RADIAL or the file's)
  bool ignore_gt_intrinsics = false;  // --ignore-gt-intrinsics
  bool fixed_intrinsics = false;      // --fixed-intrinsics: the default camera is not refined

  // Throws comic::Error(kInvalidArgument) naming --camera-model for an unknown model name.
  void Check() const;
};

struct ResolvedCamera {
  Camera camera;       // at the size of the frames as used
  std::string source;  // "file calib.txt", "ground truth poses.txt", "EXIF ..." or "default: ..."
  // Where the camera (or the prior of a self-calibrating one) came from: "file", "ground_truth",
  // "exif" or "default".
  std::string origin;
  // No calibration was given: the default camera, whose intrinsics are unknown (a COLMAP export
  // lets COLMAP refine them).
  bool self_calibrating = false;
  // The run refines the focal length and distortion: self_calibrating && !fixed_intrinsics.
  bool refine_intrinsics = false;
};

// The camera of a run on frames stored at `source_size` and used at `frame_size`, by the rule
// above; `gt_path` (--gt) names the ground truth in the camera's source, `exif` is the frames'
// EXIF focal (FindExifFocalPrior; its focal is at `source_size`). Throws comic::Error as
// LoadCameraCalibration and ConvertCameraModel do.
ResolvedCamera ResolveCamera(const CameraChoice& choice, const cv::Size& source_size,
                             const cv::Size& frame_size,
                             const std::optional<FrameGroundTruth>& ground_truth,
                             const std::string& gt_path = "", const ExifFocalPrior& exif = {});

// --intrinsics FILE as a camera of the frames as used. Throws comic::Error for a missing or
// malformed file (kNotFound, kInvalidData), a file made for another image size (kInvalidData) or
// a camera `model` cannot hold (kInvalidArgument).
Camera LoadCameraCalibration(const std::string& path, const cv::Size& source_size,
                             const cv::Size& frame_size,
                             const std::optional<CameraModelId>& model = std::nullopt);

// The model named by --camera-model; throws comic::Error(kInvalidArgument) listing the names.
CameraModelId ParseCameraModel(const std::string& name);

// `camera` as `model` when that loses nothing (a one-focal model needs fx == fy; the target must
// hold every non-zero distortion coefficient); throws comic::Error(kInvalidArgument) naming
// --camera-model otherwise.
Camera ConvertCameraModel(const Camera& camera, CameraModelId model);

}  // namespace comic::sfm
