// Camera intrinsics: one of COLMAP's models (sfm/camera_model.h) with its parameters.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "sfm/camera_model.h"

namespace comic::sfm {

// Intrinsics in OpenCV's pixel convention: pixel centres at integer coordinates, so the
// top-left pixel's centre is (0, 0). (COLMAP puts it at (0.5, 0.5); io's COLMAP writers convert.)
// The parameters are kept by name whatever the model: models with one focal length have
// fx == fy, and distortion coefficients a model does not have are 0.
struct Camera {
  CameraModelId model = CameraModelId::kPinhole;
  int width = 0;    // pixels
  int height = 0;   // pixels
  double fx = 0.0;  // focal length in pixels, x
  double fy = 0.0;  // focal length in pixels, y
  double cx = 0.0;  // principal point x, pixels
  double cy = 0.0;  // principal point y, pixels
  double k1 = 0.0;  // radial distortion (SIMPLE_RADIAL's k, RADIAL, OPENCV)
  double k2 = 0.0;  // radial distortion (RADIAL, OPENCV)
  double p1 = 0.0;  // tangential distortion (OPENCV)
  double p2 = 0.0;  // tangential distortion (OPENCV)

  // The default when nothing better is known: f = 1.2 · max(w, h), principal point at the
  // image centre ((w − 1)/2, (h − 1)/2), no distortion; PINHOLE unless another model is asked
  // for (COLMAP's feature extractor starts from the same focal, SIMPLE_RADIAL with k = 0).
  static Camera FromImageSize(int width, int height, CameraModelId model = CameraModelId::kPinhole);

  // A camera from COLMAP-ordered parameters (sfm/camera_model.h), in OpenCV's pixel convention.
  // Throws comic::Error(kInvalidArgument) for a wrong parameter count or an invalid camera.
  static Camera FromParams(CameraModelId model, int width, int height,
                           const std::vector<double>& params);
  // The parameters in COLMAP's order for `model` (OpenCV's pixel convention).
  std::vector<double> Params() const;
  // Sets the parameters from COLMAP's order for `model` (no check).
  void SetParams(const double* params);

  // The same camera for images resized by `factor` (both axes): focal lengths scale, and the
  // principal point maps so that pixel areas, not pixel centres, scale. Distortion acts on
  // normalised coordinates and stays.
  Camera Scaled(double factor) const;

  // The pinhole matrix (distortion left out).
  Eigen::Matrix3d K() const;
  bool HasDistortion() const { return k1 != 0.0 || k2 != 0.0 || p1 != 0.0 || p2 != 0.0; }

  // Pixel of a point on the normalised image plane (x/z, y/z), distortion applied.
  Eigen::Vector2d ImageFromCam(const Eigen::Vector2d& normalized) const;
  // Normalised (undistorted) point of a pixel (iterative undistortion).
  Eigen::Vector2d CamFromImage(const Eigen::Vector2d& pixel) const;
  // The pixel an ideal pinhole camera with this K would see: K · CamFromImage(pixel).
  Eigen::Vector2d UndistortPixel(const Eigen::Vector2d& pixel) const;

  // "SIMPLE_RADIAL f=1843.2 cx=... k=..." for logs and messages.
  std::string Describe() const;

  // Throws comic::Error(kInvalidArgument) for non-positive sizes or focal lengths, non-finite
  // parameters, fx != fy in a one-focal model or a distortion coefficient the model lacks.
  void Check() const;
};

// The range of values a real camera of its size has, checked on calibrations read from files
// (issue 29: cx = 1e300 ran to 0 verified pairs and exit 0; fx = 1e308 ended in "USAC threshold
// must be > 0"): focal lengths in [kMinFocalFactor, kMaxFocalFactor] · max(width, height) (a
// 180° lens to a 0.6° telephoto), the principal point within one image size around the image,
// distortion coefficients within ±kMaxDistortion.
inline constexpr double kMinFocalFactor = 0.01;
inline constexpr double kMaxFocalFactor = 100.0;
inline constexpr double kMaxDistortion = 100.0;

// Camera::Check, then the ranges above. Throws comic::Error(kInvalidData) naming the value, its
// range and the camera's size; callers put the file's name in front.
void CheckCameraValuesPlausible(const Camera& camera);

}  // namespace comic::sfm
