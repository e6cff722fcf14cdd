// Camera calibration files for --intrinsics, in the formats people have:
//   numbers   "fx fy cx cy" (PINHOLE) or "fx fy cx cy k1 [k2 [p1 p2]]" (OPENCV, missing
//             coefficients 0), or a 3x3 K or 3x4 P (KITTI's calib.txt;
//             io/datasets/ground_truth_cameras.h)
//   opencv    an OpenCV FileStorage file (.yml, .yaml, .xml, or content starting "%YAML" or
//             "<?xml"): camera_matrix (3x3) and distortion_coefficients (4, 5 or 8 values, OpenCV's
//             k1 k2 p1 p2 [k3 [k4 k5 k6]]); k3..k6 must be 0 (the OPENCV model has no k3), the
//             optional image_width / image_height give the size it was made for
//   colmap    a COLMAP cameras.txt: its first camera, any of SIMPLE_PINHOLE, PINHOLE,
//             SIMPLE_RADIAL, RADIAL, OPENCV (principal point converted from COLMAP's pixel
//             convention)
// The result is a COLMAP model name with its parameters in COLMAP's order, in OpenCV's pixel
// convention (top-left pixel centre at (0, 0)).
#pragma once

#include <string>
#include <vector>

namespace comic::io {

struct CameraCalibration {
  std::string model;           // COLMAP's name: "PINHOLE", "OPENCV", ...
  std::vector<double> params;  // in the model's order, OpenCV pixel convention
  int width = 0;               // image size the file states (0: none stated)
  int height = 0;
  std::string format;  // "numbers", "K", "P", "opencv" or "colmap"
};

// Throws comic::Error: kNotFound for a missing file, kInvalidData with one line naming the file
// for anything it cannot use (unknown format, wrong count, k3 != 0, unsupported model, ...).
CameraCalibration ReadCameraCalibrationFile(const std::string& path);

}  // namespace comic::io
