// The camera a scene is rendered through: a perspective lens with the distortion of COLMAP's
// OPENCV model (k1, k2, p1, p2; PINHOLE when they are all 0), in OpenCV's pixel convention (the
// top-left pixel's centre at (0, 0)). A normalised point (u, v) on the plane z = 1 is distorted as
//   u' = u (1 + k1 r² + k2 r⁴) + 2 p1 u v + p2 (r² + 2 u²)
//   v' = v (1 + k1 r² + k2 r⁴) + p1 (r² + 2 v²) + 2 p2 u v,   r² = u² + v²,
// then mapped to the pixel (fx u' + cx, fy v' + cy).
//
// Why a copy of the formula here: sfm/camera_model.h holds the same model, but render/ sits
// beside io/ under everything else and may not include sfm/; io/ holds files, not geometry. The
// formula is a dozen lines; tests/render/lens_test.cc checks this copy against sfm's at many
// points, so the two cannot drift apart unnoticed.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

namespace comic::render {

struct Lens {
  int width = 640;  // pixels
  int height = 480;
  double fx = 500.0;  // pixels
  double fy = 500.0;
  double cx = 319.5;  // OpenCV convention
  double cy = 239.5;
  double k1 = 0.0;  // OPENCV distortion
  double k2 = 0.0;
  double p1 = 0.0;
  double p2 = 0.0;

  bool HasDistortion() const { return k1 != 0.0 || k2 != 0.0 || p1 != 0.0 || p2 != 0.0; }
  // The distorted normalised point (u', v') of (u, v).
  Eigen::Vector2d Distort(const Eigen::Vector2d& uv) const;
  Eigen::Vector2d PixelFromNormalized(const Eigen::Vector2d& uv) const;
  // The inverse: Newton's method on the distortion with its analytic Jacobian (at most 100
  // steps, until the step is below 1e-12 of the point's norm), as COLMAP's
  // IterativeUndistortion.
  Eigen::Vector2d NormalizedFromPixel(const Eigen::Vector2d& pixel) const;
  // The normalised point whose distortion is `distorted` (Newton from `guess`).
  Eigen::Vector2d Undistort(const Eigen::Vector2d& distorted, const Eigen::Vector2d& guess) const;

  // "PINHOLE" (fx fy cx cy) or "OPENCV" (fx fy cx cy k1 k2 p1 p2), COLMAP's names.
  std::string ColmapModelName() const;
  // The parameters in that model's order, the principal point in COLMAP's convention (+0.5).
  std::vector<double> ColmapParams() const;

  // Throws comic::Error(kInvalidArgument) naming the field: sizes in 1..16384, focal lengths > 0,
  // finite values, and a distortion that stays one-to-one over the image (checked along the
  // image's diagonals).
  void Check() const;
};

}  // namespace comic::render
