// --intrinsics FILE as a camera of the frames as used: the file describes the frames as stored
// ('fx fy cx cy', a 3x3 K or a 3x4 P such as KITTI's calib.txt, OpenCV pixel convention), and a
// resized sequence scales it (pixel centre c -> (c + 0.5) s - 0.5, sfm::Camera::Scaled).
#pragma once

#include <opencv2/core/types.hpp>
#include <string>

#include "sfm/camera.h"

namespace comic::apps {

// Throws comic::Error for a missing or malformed file (io::ReadIntrinsicsFile) or a K with skew.
sfm::Camera LoadCameraIntrinsics(const std::string& path, const cv::Size& source_size,
                                 const cv::Size& frame_size);

}  // namespace comic::apps
