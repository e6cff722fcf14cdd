#include "apps/common/camera_intrinsics.h"

#include "io/ground_truth_cameras.h"
#include "sfm/evaluation/ground_truth.h"

namespace comic::apps {

sfm::Camera LoadCameraIntrinsics(const std::string& path, const cv::Size& source_size,
                                 const cv::Size& frame_size) {
  const sfm::Camera source_camera =
      sfm::CameraFromK(io::ReadIntrinsicsFile(path), source_size.width, source_size.height);
  const double scale = static_cast<double>(frame_size.height) / source_size.height;
  sfm::Camera camera = scale == 1.0 ? source_camera : source_camera.Scaled(scale);
  camera.width = frame_size.width;
  camera.height = frame_size.height;
  return camera;
}

}  // namespace comic::apps
