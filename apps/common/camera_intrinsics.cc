#include "apps/common/camera_intrinsics.h"

#include "io/core/error.h"
#include "io/datasets/camera_calibration_file.h"

namespace comic::apps {

sfm::CameraModelId ParseCameraModelFlag(const std::string& name) {
  const auto model = sfm::CameraModelFromName(name);
  COMIC_CHECK(
      model.has_value(), kInvalidArgument,
      "--camera-model: expected one of " << sfm::CameraModelNames() << ", got '" << name << "'");
  return *model;
}

sfm::Camera ConvertCameraModel(const sfm::Camera& camera, sfm::CameraModelId model) {
  if (camera.model == model) return camera;
  sfm::Camera converted = camera;
  converted.model = model;
  try {
    converted.Check();
  } catch (const Error&) {
    throw Error(ErrorKind::kInvalidArgument, "--camera-model " + sfm::CameraModelName(model) +
                                                 " cannot hold the camera " + camera.Describe() +
                                                 " without losing parameters");
  }
  return converted;
}

sfm::Camera LoadCameraIntrinsics(const std::string& path, const cv::Size& source_size,
                                 const cv::Size& frame_size,
                                 const std::optional<sfm::CameraModelId>& model) {
  const io::CameraCalibration calibration = io::ReadCameraCalibrationFile(path);
  COMIC_CHECK(
      (calibration.width == 0 && calibration.height == 0) ||
          (calibration.width == source_size.width && calibration.height == source_size.height),
      kInvalidData,
      path << ": calibration is for " << calibration.width << "x" << calibration.height
           << " images, the frames are " << source_size.width << "x" << source_size.height);
  const auto file_model = sfm::CameraModelFromName(calibration.model);
  COMIC_CHECK(file_model.has_value(), kInvalidData,
              path << ": unsupported camera model " << calibration.model);
  sfm::Camera source_camera;
  try {
    source_camera = sfm::Camera::FromParams(*file_model, source_size.width, source_size.height,
                                            calibration.params);
    sfm::CheckCameraValuesPlausible(source_camera);
  } catch (const Error& error) {
    throw Error(ErrorKind::kInvalidData, path + ": " + error.what());
  }
  if (model) source_camera = ConvertCameraModel(source_camera, *model);
  const double scale = static_cast<double>(frame_size.height) / source_size.height;
  sfm::Camera camera = scale == 1.0 ? source_camera : source_camera.Scaled(scale);
  camera.width = frame_size.width;
  camera.height = frame_size.height;
  return camera;
}

}  // namespace comic::apps
