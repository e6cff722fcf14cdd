// Hessian blob detector (Beaudet 1978), a baseline of the paper (§5.1): the determinant of the
// Hessian of the Gaussian-smoothed image, det H = Lxx·Lyy − Lxy², and its positive local maxima
// (bright and dark blobs; saddles have det H < 0). OpenCV has no ready one.
//
// Single fixed scale σ = 2 px by default (like the Harris baseline: support ≈ 3σ = 6 px, well
// inside the 23x23 matching patch). Lengths are pixels of the image given to Detect — the
// evaluation apps resize frames to height 700 first (paper §5.1).
#pragma once

#include <string>

#include "frontend/detector.h"

namespace comic::frontend {

struct HessianDetectorOptions {
  // Gaussian scale σ of the second derivatives, in pixels.
  double sigma = 2.0;
  // Non-maximum suppression window radius in pixels (1 = 3x3) and image border without peaks.
  int nms_radius = 1;
  int border = 3;
  // det H cut-off applied inside Detect (grey levels² per pixel⁴); 0 returns every positive
  // maximum so that threshold equalisation picks the cut-off.
  double min_response = 0.0;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

class HessianDetector : public Detector {
 public:
  explicit HessianDetector(const HessianDetectorOptions& options = {});

  std::string Name() const override { return "hessian"; }
  // Features at the det H maxima (sub-pixel), response = det H, scale = σ.
  FeatureSet Detect(const cv::Mat& gray) const override;

  // The determinant-of-Hessian map (CV_32FC1, same size as `gray`).
  cv::Mat DeterminantOfHessian(const cv::Mat& gray) const;

  const HessianDetectorOptions& options() const { return options_; }

 private:
  HessianDetectorOptions options_;
};

}  // namespace comic::frontend
