#include "sfm/run/camera_resolution.h"

#include "io/core/error.h"
#include "io/datasets/camera_calibration_file.h"

namespace comic::sfm {

void CameraChoice::Check() const {
  if (!camera_model.empty()) ParseCameraModel(camera_model);
}

CameraModelId ParseCameraModel(const std::string& name) {
  const auto model = CameraModelFromName(name);
  COMIC_CHECK(model.has_value(), kInvalidArgument,
              "--camera-model: expected one of " << CameraModelNames() << ", got '" << name << "'");
  return *model;
}

Camera ConvertCameraModel(const Camera& camera, CameraModelId model) {
  if (camera.model == model) return camera;
  Camera converted = camera;
  converted.model = model;
  try {
    converted.Check();
  } catch (const Error&) {
    throw Error(ErrorKind::kInvalidArgument, "--camera-model " + CameraModelName(model) +
                                                 " cannot hold the camera " + camera.Describe() +
                                                 " without losing parameters");
  }
  return converted;
}

Camera LoadCameraCalibration(const std::string& path, const cv::Size& source_size,
                             const cv::Size& frame_size,
                             const std::optional<CameraModelId>& model) {
  const io::CameraCalibration calibration = io::ReadCameraCalibrationFile(path);
  COMIC_CHECK(
      (calibration.width == 0 && calibration.height == 0) ||
          (calibration.width == source_size.width && calibration.height == source_size.height),
      kInvalidData,
      path << ": calibration is for " << calibration.width << "x" << calibration.height
           << " images, the frames are " << source_size.width << "x" << source_size.height);
  const auto file_model = CameraModelFromName(calibration.model);
  COMIC_CHECK(file_model.has_value(), kInvalidData,
              path << ": unsupported camera model " << calibration.model);
  Camera source_camera;
  try {
    source_camera =
        Camera::FromParams(*file_model, source_size.width, source_size.height, calibration.params);
    // Values no lens has (issue 29: cx = 1e300 ran to 0 verified pairs with exit 0).
    CheckCameraValuesPlausible(source_camera);
  } catch (const Error& error) {
    throw Error(ErrorKind::kInvalidData, path + ": " + error.what());
  }
  if (model) source_camera = ConvertCameraModel(source_camera, *model);
  const double scale = static_cast<double>(frame_size.height) / source_size.height;
  Camera camera = scale == 1.0 ? source_camera : source_camera.Scaled(scale);
  camera.width = frame_size.width;
  camera.height = frame_size.height;
  return camera;
}

namespace {

// No calibration: COLMAP's default for an unknown camera (SIMPLE_RADIAL, k = 0, the principal
// point at the centre) with the focal length the photos' EXIF states, else f = 1.2 max(w, h).
ResolvedCamera SelfCalibratingCamera(const CameraChoice& choice, const cv::Size& source_size,
                                     const cv::Size& frame_size, CameraModelId model,
                                     const ExifFocalPrior& exif) {
  ResolvedCamera resolved;
  resolved.camera = Camera::FromImageSize(frame_size.width, frame_size.height, model);
  if (exif.focal_px) {
    const double scale = static_cast<double>(frame_size.height) / source_size.height;
    resolved.camera.fx = resolved.camera.fy = *exif.focal_px * scale;
    resolved.origin = "exif";
    resolved.source = exif.description;
  } else {
    resolved.origin = "default";
    resolved.source = "default: f = 1.2 max(w, h), principal point at the centre";
    if (!exif.description.empty()) resolved.source += " (" + exif.description + ")";
  }
  resolved.self_calibrating = true;
  resolved.refine_intrinsics = !choice.fixed_intrinsics;
  resolved.source +=
      choice.fixed_intrinsics ? ", held fixed" : ", refined once the model constrains it";
  return resolved;
}

}  // namespace

ResolvedCamera ResolveCamera(const CameraChoice& choice, const cv::Size& source_size,
                             const cv::Size& frame_size,
                             const std::optional<FrameGroundTruth>& ground_truth,
                             const std::string& gt_path, const ExifFocalPrior& exif) {
  std::optional<CameraModelId> model;
  if (!choice.camera_model.empty()) model = ParseCameraModel(choice.camera_model);
  ResolvedCamera resolved;
  if (!choice.intrinsics.empty()) {
    resolved.camera = LoadCameraCalibration(choice.intrinsics, source_size, frame_size, model);
    resolved.source = "file " + choice.intrinsics;
    resolved.origin = "file";
  } else if (ground_truth && ground_truth->camera && !choice.ignore_gt_intrinsics) {
    resolved.camera = *ground_truth->camera;
    if (model) resolved.camera = ConvertCameraModel(resolved.camera, *model);
    resolved.source = "ground truth " + gt_path;
    resolved.origin = "ground_truth";
  } else {
    resolved = SelfCalibratingCamera(choice, source_size, frame_size,
                                     model.value_or(CameraModelId::kSimpleRadial), exif);
  }
  resolved.camera.width = frame_size.width;
  resolved.camera.height = frame_size.height;
  return resolved;
}

}  // namespace comic::sfm
