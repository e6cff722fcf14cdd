// KITTI odometry ground truth: camera poses (`poses.txt`) and projection matrices (`calib.txt`).
//
//   auto world_from_camera = comic::io::ReadKittiPoses("kitti06/poses.txt");    // one per frame
//   cv::Matx33d K = comic::io::ReadKittiIntrinsics("kitti06/calib.txt", 0);    // from P0
//
// poses.txt: line i holds the 12 numbers of the 3x4 matrix [R | t], row-major, mapping a point in
// camera-i coordinates to world coordinates (X_w = R X_c + t; world = camera 0 of the sequence;
// x right, y down, z forward; metres). calib.txt: lines "P0: p00 .. p23" (the "P0:" label is
// optional) holding 3x4 projection matrices of the rectified cameras, P = K [I | t]; the pixel
// convention is OpenCV's (pixel centres at integer coordinates).
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace comic::io {

// Reads every pose of a KITTI poses.txt. Throws comic::Error: kNotFound for a missing file,
// kInvalidData naming the file and line for a line without exactly 12 numbers or whose rotation
// is not orthonormal (tolerance 1e-4), and for a file without poses.
std::vector<cv::Matx34d> ReadKittiPoses(const std::string& path);

// Reads projection matrix P<camera> (the camera-th line) of a KITTI calib.txt. Throws
// comic::Error(kInvalidData) naming the file if it has fewer lines or a line is malformed.
cv::Matx34d ReadKittiProjection(const std::string& path, int camera = 0);

// The intrinsics K = P(:, 0:3) of projection matrix P<camera> of calib.txt (rectified KITTI
// cameras share one K; P's last column holds only the stereo baseline). Throws like
// ReadKittiProjection, and kInvalidData if K is not upper triangular with positive focal lengths.
cv::Matx33d ReadKittiIntrinsics(const std::string& path, int camera = 0);

}  // namespace comic::io
