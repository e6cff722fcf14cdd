// Fuzz target: the --intrinsics calibration reader with the value ranges every camera read from a
// file is held to (issue 29: cx = 1e300 ran to 0 verified pairs with exit 0, fx = 1e308 ended in
// "USAC threshold must be > 0"). The bytes are read as each calibration format, at the size the
// file states or at a few frame sizes; a camera that sfm::CheckCameraValuesPlausible accepts must
// then behave as the reconstruction uses it: scaled to a resized sequence, every pixel of a grid
// over the image (and a margin) undistorted and projected back to finite values. A non-finite
// value from an accepted camera is a finding (the range is too wide); comic::Error is the
// expected answer to anything else.
#include <cmath>
#include <optional>
#include <vector>

#include "fuzz/fuzz_input.h"
#include "io/core/error.h"
#include "io/datasets/camera_calibration_file.h"
#include "sfm/camera.h"

namespace {

using comic::sfm::Camera;

void ExpectFinite(const Eigen::Vector2d& value) {
  if (!std::isfinite(value.x()) || !std::isfinite(value.y())) __builtin_trap();
}

// What the pipeline does with an accepted camera: resize, undistort, project.
void Exercise(const Camera& accepted) {
  for (const double scale : {1.0, 0.5}) {
    const Camera camera = scale == 1.0 ? accepted : accepted.Scaled(scale);
    camera.Check();
    for (int i = 0; i <= 4; ++i) {
      for (int j = 0; j <= 4; ++j) {
        const Eigen::Vector2d pixel((i - 0.5) * camera.width / 3.0,
                                    (j - 0.5) * camera.height / 3.0);
        const Eigen::Vector2d normalized = camera.CamFromImage(pixel);
        ExpectFinite(normalized);
        ExpectFinite(camera.ImageFromCam(normalized));
        ExpectFinite(camera.UndistortPixel(pixel));
      }
    }
  }
}

void TryCamera(const comic::io::CameraCalibration& calibration, int width, int height) {
  const std::optional<comic::sfm::CameraModelId> model =
      comic::sfm::CameraModelFromName(calibration.model);
  if (!model || width < 1 || height < 1) return;
  try {
    const Camera camera = Camera::FromParams(*model, width, height, calibration.params);
    comic::sfm::CheckCameraValuesPlausible(camera);
    Exercise(camera);
  } catch (const comic::Error&) {
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  for (const char* name : {"calib.yml", "cameras.txt", "calib.txt"}) {
    const std::string path = comic::fuzz::WriteInput(name, data, size);
    try {
      const comic::io::CameraCalibration calibration = comic::io::ReadCameraCalibrationFile(path);
      if (calibration.width > 0 && calibration.height > 0) {
        TryCamera(calibration, calibration.width, calibration.height);
      } else {
        for (const auto& [width, height] :
             {std::pair{1226, 370}, std::pair{64, 48}, std::pair{4000, 3000}}) {
          TryCamera(calibration, width, height);
        }
      }
    } catch (const comic::Error&) {
    }
  }
  return 0;
}
