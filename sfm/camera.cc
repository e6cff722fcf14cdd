#include "sfm/camera.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <utility>

#include "io/core/error.h"

namespace comic::sfm {

Camera Camera::FromImageSize(int width, int height, CameraModelId model) {
  Camera camera;
  camera.model = model;
  camera.width = width;
  camera.height = height;
  camera.fx = camera.fy = 1.2 * std::max(width, height);
  camera.cx = (width - 1) / 2.0;
  camera.cy = (height - 1) / 2.0;
  camera.Check();
  return camera;
}

Camera Camera::FromParams(CameraModelId model, int width, int height,
                          const std::vector<double>& params) {
  COMIC_CHECK(static_cast<int>(params.size()) == CameraModelNumParams(model), kInvalidArgument,
              CameraModelName(model) << " takes " << CameraModelNumParams(model) << " parameters ("
                                     << CameraModelParamsInfo(model) << "), got " << params.size());
  Camera camera;
  camera.model = model;
  camera.width = width;
  camera.height = height;
  camera.SetParams(params.data());
  camera.Check();
  return camera;
}

std::vector<double> Camera::Params() const {
  switch (model) {
    case CameraModelId::kSimplePinhole:
      return {fx, cx, cy};
    case CameraModelId::kPinhole:
      return {fx, fy, cx, cy};
    case CameraModelId::kSimpleRadial:
      return {fx, cx, cy, k1};
    case CameraModelId::kRadial:
      return {fx, cx, cy, k1, k2};
    case CameraModelId::kOpenCV:
      return {fx, fy, cx, cy, k1, k2, p1, p2};
  }
  return {};
}

void Camera::SetParams(const double* params) {
  const int pp = CameraModelPrincipalPointIndex(model);
  fx = params[0];
  fy = params[pp == 1 ? 0 : 1];
  cx = params[pp];
  cy = params[pp + 1];
  const int num_extra = CameraModelNumExtraParams(model);
  const double* extra = params + pp + 2;
  k1 = num_extra > 0 ? extra[0] : 0.0;
  k2 = num_extra > 1 ? extra[1] : 0.0;
  p1 = num_extra > 2 ? extra[2] : 0.0;
  p2 = num_extra > 3 ? extra[3] : 0.0;
}

Camera Camera::Scaled(double factor) const {
  COMIC_CHECK(factor > 0, kInvalidArgument, "camera scale factor must be > 0, got " << factor);
  Camera scaled = *this;
  scaled.width = static_cast<int>(std::lround(width * factor));
  scaled.height = static_cast<int>(std::lround(height * factor));
  scaled.fx = fx * factor;
  scaled.fy = fy * factor;
  // Pixel centre c maps to (c + 0.5) · factor − 0.5.
  scaled.cx = (cx + 0.5) * factor - 0.5;
  scaled.cy = (cy + 0.5) * factor - 0.5;
  return scaled;
}

Eigen::Matrix3d Camera::K() const {
  Eigen::Matrix3d k;
  k << fx, 0.0, cx, 0.0, fy, cy, 0.0, 0.0, 1.0;
  return k;
}

Eigen::Vector2d Camera::ImageFromCam(const Eigen::Vector2d& normalized) const {
  if (!HasDistortion()) {
    return {fx * normalized.x() + cx, fy * normalized.y() + cy};
  }
  const std::vector<double> params = Params();
  Eigen::Vector2d pixel;
  ImageFromNormalized(model, params.data(), normalized.x(), normalized.y(), &pixel.x(), &pixel.y());
  return pixel;
}

Eigen::Vector2d Camera::CamFromImage(const Eigen::Vector2d& pixel) const {
  if (!HasDistortion()) return {(pixel.x() - cx) / fx, (pixel.y() - cy) / fy};
  const std::vector<double> params = Params();
  return NormalizedFromImage(model, params.data(), pixel);
}

Eigen::Vector2d Camera::UndistortPixel(const Eigen::Vector2d& pixel) const {
  if (!HasDistortion()) return pixel;
  const Eigen::Vector2d normalized = CamFromImage(pixel);
  return {fx * normalized.x() + cx, fy * normalized.y() + cy};
}

std::string Camera::Describe() const {
  std::ostringstream text;
  text << CameraModelName(model);
  if (CameraModelNumFocalParams(model) == 1) {
    text << " f=" << fx;
  } else {
    text << " fx=" << fx << " fy=" << fy;
  }
  text << " cx=" << cx << " cy=" << cy;
  switch (model) {
    case CameraModelId::kSimpleRadial:
      text << " k=" << k1;
      break;
    case CameraModelId::kRadial:
      text << " k1=" << k1 << " k2=" << k2;
      break;
    case CameraModelId::kOpenCV:
      text << " k1=" << k1 << " k2=" << k2 << " p1=" << p1 << " p2=" << p2;
      break;
    default:
      break;
  }
  return text.str();
}

void Camera::Check() const {
  COMIC_CHECK(
      CameraModelFromId(static_cast<int>(model)).has_value(), kInvalidArgument,
      "camera model id " << static_cast<int>(model) << " is not one of " << CameraModelNames());
  COMIC_CHECK(width > 0 && height > 0, kInvalidArgument,
              "camera size must be positive, got " << width << "x" << height);
  COMIC_CHECK(fx > 0 && fy > 0 && std::isfinite(fx) && std::isfinite(fy), kInvalidArgument,
              "camera focal lengths must be positive, got fx=" << fx << " fy=" << fy);
  COMIC_CHECK(std::isfinite(cx) && std::isfinite(cy), kInvalidArgument,
              "camera principal point must be finite");
  COMIC_CHECK(CameraModelNumFocalParams(model) == 2 || fx == fy, kInvalidArgument,
              CameraModelName(model) << " has one focal length, got fx=" << fx << " fy=" << fy);
  COMIC_CHECK(std::isfinite(k1) && std::isfinite(k2) && std::isfinite(p1) && std::isfinite(p2),
              kInvalidArgument, "camera distortion coefficients must be finite");
  const int num_extra = CameraModelNumExtraParams(model);
  COMIC_CHECK((num_extra > 0 || k1 == 0.0) && (num_extra > 1 || k2 == 0.0) &&
                  (num_extra > 2 || (p1 == 0.0 && p2 == 0.0)),
              kInvalidArgument,
              CameraModelName(model) << " (" << CameraModelParamsInfo(model)
                                     << ") cannot hold the distortion coefficients given");
}

void CheckCameraValuesPlausible(const Camera& camera) {
  try {
    camera.Check();
  } catch (const Error& e) {
    throw Error(ErrorKind::kInvalidData, e.what());
  }
  const double size = std::max(camera.width, camera.height);
  for (const auto& [name, value] : {std::pair<const char*, double>{"fx", camera.fx},
                                    std::pair<const char*, double>{"fy", camera.fy}}) {
    COMIC_CHECK(value >= kMinFocalFactor * size && value <= kMaxFocalFactor * size, kInvalidData,
                "focal length " << name << " = " << value << " px is outside ["
                                << kMinFocalFactor * size << ", " << kMaxFocalFactor * size
                                << "] px, what a lens on " << camera.width << "x" << camera.height
                                << " images can have");
  }
  COMIC_CHECK(camera.cx >= -camera.width && camera.cx <= 2.0 * camera.width, kInvalidData,
              "principal point cx = " << camera.cx << " px is outside [" << -camera.width << ", "
                                      << 2 * camera.width << "] px for images " << camera.width
                                      << " px wide");
  COMIC_CHECK(camera.cy >= -camera.height && camera.cy <= 2.0 * camera.height, kInvalidData,
              "principal point cy = " << camera.cy << " px is outside [" << -camera.height << ", "
                                      << 2 * camera.height << "] px for images " << camera.height
                                      << " px high");
  for (const auto& [name, value] : {std::pair<const char*, double>{"k1", camera.k1},
                                    std::pair<const char*, double>{"k2", camera.k2},
                                    std::pair<const char*, double>{"p1", camera.p1},
                                    std::pair<const char*, double>{"p2", camera.p2}}) {
    COMIC_CHECK(std::abs(value) <= kMaxDistortion, kInvalidData,
                "distortion coefficient " << name << " = " << value << " is outside ["
                                          << -kMaxDistortion << ", " << kMaxDistortion << "]");
  }
}

}  // namespace comic::sfm
