// Harris corner detector (Harris & Stephens 1988), the paper's main baseline (§5.1): the
// cornerness R = det(M) − k·trace(M)² of the Gaussian-weighted second-moment matrix M of the
// image gradients, and its local maxima.
//
// Single fixed scale, as the paper compares the non-invariant detectors on video where
// consecutive frames differ little in scale. The defaults (σ_D = 1 px, σ_I = 2 px) are the usual
// "Harris at one scale" setting and keep the detector's support (≈ 3σ_I = 6 px) well inside the
// 23x23 matching patch. All lengths are in pixels of the image given to Detect — the evaluation
// apps resize frames to height 700 first (paper §5.1).
#pragma once

#include <string>

#include "frontend/baselines/response_peaks.h"
#include "frontend/detector.h"

namespace comic::frontend {

struct HarrisDetectorOptions {
  // Gaussian smoothing before differentiation, σ_D in pixels.
  double derivative_sigma = 1.0;
  // Gaussian window of the second-moment matrix, σ_I in pixels.
  double integration_sigma = 2.0;
  // Harris' k in det − k·trace² (dimensionless; 0.04 is the customary value).
  double k = 0.04;
  // Non-maximum suppression window radius in pixels (1 = 3x3) and image border without peaks.
  int nms_radius = 1;
  int border = 3;
  // Cornerness cut-off applied inside Detect (grey levels⁴ per pixel⁴, gradients measured in
  // grey levels per pixel); 0 returns every positive maximum so that threshold equalisation
  // picks the cut-off.
  double min_response = 0.0;

  // Throws comic::Error(kInvalidArgument) naming the bad field.
  void Check() const;
};

class HarrisDetector : public Detector {
 public:
  explicit HarrisDetector(const HarrisDetectorOptions& options = {});

  std::string Name() const override { return "harris"; }
  // Features at the cornerness maxima (sub-pixel), response = R, scale = σ_I.
  FeatureSet Detect(const cv::Mat& gray) const override;

  // The cornerness map R (CV_32FC1, same size as `gray`).
  cv::Mat Cornerness(const cv::Mat& gray) const;

  const HarrisDetectorOptions& options() const { return options_; }

 private:
  HarrisDetectorOptions options_;
};

}  // namespace comic::frontend
