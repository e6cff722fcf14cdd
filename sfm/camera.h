// Pinhole camera intrinsics.
#pragma once

#include <Eigen/Core>
#include <string>

namespace comic::sfm {

// Pinhole intrinsics in OpenCV's pixel convention: pixel centres at integer coordinates, so the
// top-left pixel's centre is (0, 0). (COLMAP puts it at (0.5, 0.5); io's COLMAP writers convert.)
struct Camera {
  int width = 0;    // pixels
  int height = 0;   // pixels
  double fx = 0.0;  // focal length in pixels, x
  double fy = 0.0;  // focal length in pixels, y
  double cx = 0.0;  // principal point x, pixels
  double cy = 0.0;  // principal point y, pixels

  // The default when nothing better is known: f = 1.2 · max(w, h), principal point at the
  // image centre ((w − 1)/2, (h − 1)/2).
  static Camera FromImageSize(int width, int height);

  // The same camera for images resized by `factor` (both axes): focal lengths scale, and the
  // principal point maps so that pixel areas, not pixel centres, scale.
  Camera Scaled(double factor) const;

  Eigen::Matrix3d K() const;

  // Throws comic::Error(kInvalidArgument) for non-positive sizes or focal lengths.
  void Check() const;
};

}  // namespace comic::sfm
